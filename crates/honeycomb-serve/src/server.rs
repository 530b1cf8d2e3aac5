//! HTTP and WebSocket: the page's assets at fixed paths and one WebSocket at `/ws`. Each page
//! gets every update the editor broadcasts; a page that falls behind is sent the mesh and the
//! newest state again. Only pages served from this server may open the WebSocket: a browser
//! lets any site open one to 127.0.0.1, and that site could then edit, save and overwrite.

use crate::assets::{lookup, Asset, MISSING_HINT};
use crate::editor::{Command, Download, Page};
use crate::protocol::{error_message, ClientMessage};
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Path, State};
use axum::http::{header, HeaderMap, StatusCode, Uri};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::Router;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{SyncSender, TrySendError};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use std::time::Instant;
use tokio::sync::{broadcast, mpsc};

/// Frames above this close the connection (protocol level); messages above
/// `protocol::MAX_MESSAGE_BYTES` get an error reply and are dropped.
const MAX_FRAME_BYTES: usize = 1 << 20;

/// Commands waiting for the editor at most. An undo or a slide costs it about 10 ms (a new
/// state for every page), so a full queue is well under a second of work.
pub const COMMAND_QUEUE: usize = 64;

#[derive(Clone)]
pub struct AppState {
    pub commands: Arc<Mutex<SyncSender<Command>>>,
    pub out: broadcast::Sender<Arc<str>>,
    /// Listening on 127.0.0.1 only: the page must then also be addressed by a loopback name
    /// (a site whose own name resolves to 127.0.0.1 would otherwise pass as same-origin).
    pub loopback_only: bool,
}

/// What became of a command handed to the editor.
enum Sent {
    Queued,
    Busy,
    Gone,
}

impl AppState {
    fn try_send(&self, c: Command) -> Sent {
        let Ok(sender) = self.commands.lock() else {
            return Sent::Gone;
        };
        match sender.try_send(c) {
            Ok(()) => Sent::Queued,
            Err(TrySendError::Full(_)) => Sent::Busy,
            Err(TrySendError::Disconnected(_)) => Sent::Gone,
        }
    }

    /// Asks for the mesh and the current state on `reply`, waiting while the queue is full (a
    /// page must get them to show anything). False: the editor is gone.
    async fn hello(&self, page: u64, reply: &mpsc::UnboundedSender<Arc<str>>) -> bool {
        loop {
            match self.try_send(Command::Hello(page, reply.clone())) {
                Sent::Queued => return true,
                Sent::Busy => tokio::time::sleep(Duration::from_millis(5)).await,
                Sent::Gone => return false,
            }
        }
    }
}

/// Numbers the pages, so that their gestures (each page numbers its own from 1) stay apart.
static PAGES: AtomicU64 = AtomicU64::new(0);

pub fn router(state: AppState) -> Router {
    Router::new()
        .route("/ws", get(upgrade))
        .route("/download/{file}", get(download))
        .fallback(asset)
        .with_state(state)
}

async fn asset(uri: Uri) -> Response {
    // The page names an icon of its own, but a browser asks for this one wherever it has none
    // (a download's tab): no icon, and no 404 in its console.
    if uri.path() == "/favicon.ico" {
        return StatusCode::NO_CONTENT.into_response();
    }
    match lookup(uri.path()) {
        Asset::Found { mime, bytes } => (
            [
                (header::CONTENT_TYPE, mime),
                (header::CACHE_CONTROL, "no-cache"),
            ],
            bytes,
        )
            .into_response(),
        Asset::Missing => (StatusCode::SERVICE_UNAVAILABLE, MISSING_HINT).into_response(),
        Asset::NotFound => (StatusCode::NOT_FOUND, "not found").into_response(),
    }
}

/// `GET /download/FILE`: one of `honeycomb export`'s files, made from the current state by the
/// editor between solver steps.
async fn download(Path(file): Path<String>, uri: Uri, State(state): State<AppState>) -> Response {
    let text = |status, message: String| (status, message).into_response();
    let mime = match crate::protocol::download(&file) {
        Ok((mime, _)) => mime,
        Err(e) => return text(StatusCode::NOT_FOUND, e),
    };
    let units = match crate::protocol::download_units(uri.query()) {
        Ok(units) => units,
        Err(e) => return text(StatusCode::BAD_REQUEST, e),
    };
    let (reply, made) = tokio::sync::oneshot::channel();
    match state.try_send(Command::Download(file.clone(), units, reply)) {
        Sent::Queued => {}
        Sent::Busy => {
            return text(
                StatusCode::SERVICE_UNAVAILABLE,
                format!("the editor is busy: {file} not made; try again"),
            )
        }
        Sent::Gone => return text(StatusCode::SERVICE_UNAVAILABLE, "the editor stopped".into()),
    }
    match made.await {
        Ok(Download::Bytes(bytes)) => (
            [
                (header::CONTENT_TYPE, mime.to_string()),
                (
                    header::CONTENT_DISPOSITION,
                    format!("attachment; filename=\"{file}\""),
                ),
                (header::CACHE_CONTROL, "no-store".to_string()),
            ],
            bytes,
        )
            .into_response(),
        Ok(Download::NotHoneycomb(why)) => text(StatusCode::CONFLICT, why),
        Ok(Download::Failed(why)) => text(StatusCode::INTERNAL_SERVER_ERROR, why),
        Err(_) => text(StatusCode::SERVICE_UNAVAILABLE, "the editor stopped".into()),
    }
}

async fn upgrade(
    ws: WebSocketUpgrade,
    headers: HeaderMap,
    State(state): State<AppState>,
) -> Response {
    if !same_origin(&headers, state.loopback_only) {
        return (
            StatusCode::FORBIDDEN,
            "the editor's WebSocket is for its own page only",
        )
            .into_response();
    }
    ws.max_message_size(MAX_FRAME_BYTES)
        .max_frame_size(MAX_FRAME_BYTES)
        .on_upgrade(move |socket| page(socket, state))
}

/// A browser names the page's site in `Origin`; it must be this server (`Host`), and on a
/// loopback server a loopback name. Clients that are not browsers (the tests, the latency
/// bench, scripts) send no `Origin` and are let in.
fn same_origin(headers: &HeaderMap, loopback_only: bool) -> bool {
    let Some(origin) = headers.get(header::ORIGIN) else {
        return true;
    };
    let host = headers.get(header::HOST).and_then(|h| h.to_str().ok());
    let site = origin.to_str().ok().and_then(|o| {
        o.strip_prefix("http://")
            .or_else(|| o.strip_prefix("https://"))
    });
    let (Some(site), Some(host)) = (site, host) else {
        return false;
    };
    let name = host.rsplit_once(':').map_or(host, |(name, _port)| name);
    let loopback = ["127.0.0.1", "localhost", "[::1]"]
        .iter()
        .any(|n| name.eq_ignore_ascii_case(n));
    site.eq_ignore_ascii_case(host) && (loopback || !loopback_only)
}

async fn page(mut socket: WebSocket, state: AppState) {
    let page = PAGES.fetch_add(1, Ordering::Relaxed);
    // Subscribe before saying hello, so no update falls between the two.
    let mut updates = state.out.subscribe();
    let (reply, mut replies) = mpsc::unbounded_channel();
    if !state.hello(page, &reply).await {
        return;
    }
    loop {
        let outgoing = tokio::select! {
            incoming = socket.recv() => match incoming {
                Some(Ok(Message::Text(text))) => match ClientMessage::parse(text.as_str()) {
                    Ok(message) => {
                        let label = message.label();
                        let from = Page {
                            number: page,
                            reply: reply.clone(),
                        };
                        match state.try_send(Command::Message(message, Instant::now(), from)) {
                            Sent::Queued => continue,
                            Sent::Busy => Arc::from(
                                error_message(&format!(
                                    "the editor is busy: message {label} dropped (send fewer, \
                                     or wait for the updates)"
                                ))
                                .to_string(),
                            ),
                            Sent::Gone => return,
                        }
                    }
                    Err(e) => Arc::from(error_message(&e).to_string()),
                },
                Some(Ok(Message::Binary(_))) => Arc::from(
                    error_message("binary frames are not understood: send JSON text").to_string(),
                ),
                Some(Ok(_)) => continue, // ping, pong
                Some(Err(_)) | None => return, // closed, or a frame over the limit
            },
            r = replies.recv() => match r {
                Some(text) => text,
                None => continue,
            },
            u = updates.recv() => match u {
                Ok(text) => text,
                // Fell behind: the skipped states are stale anyway, but a skipped mesh (another
                // page loaded a save) would leave this page's states on the wrong mesh.
                Err(broadcast::error::RecvError::Lagged(_)) => {
                    if !state.hello(page, &reply).await {
                        return;
                    }
                    continue;
                }
                Err(broadcast::error::RecvError::Closed) => return,
            },
        };
        if socket
            .send(Message::Text(outgoing.as_ref().into()))
            .await
            .is_err()
        {
            return;
        }
    }
}
