//! HTTP and WebSocket: the page's assets at fixed paths and one WebSocket at `/ws`. Each page
//! gets every update the editor broadcasts; a page that falls behind skips to the newest.

use crate::assets::{lookup, Asset, MISSING_HINT};
use crate::editor::Command;
use crate::protocol::{error_message, ClientMessage};
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::State;
use axum::http::{header, StatusCode, Uri};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::Router;
use std::sync::mpsc::Sender;
use std::sync::{Arc, Mutex};
use std::time::Instant;
use tokio::sync::{broadcast, mpsc};

/// Frames above this close the connection (protocol level); messages above
/// `protocol::MAX_MESSAGE_BYTES` get an error reply and are dropped.
const MAX_FRAME_BYTES: usize = 1 << 20;

#[derive(Clone)]
pub struct AppState {
    pub commands: Arc<Mutex<Sender<Command>>>,
    pub out: broadcast::Sender<Arc<str>>,
}

impl AppState {
    fn send(&self, c: Command) -> bool {
        self.commands
            .lock()
            .map(|s| s.send(c).is_ok())
            .unwrap_or(false)
    }
}

pub fn router(state: AppState) -> Router {
    Router::new()
        .route("/ws", get(upgrade))
        .fallback(asset)
        .with_state(state)
}

async fn asset(uri: Uri) -> Response {
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

async fn upgrade(ws: WebSocketUpgrade, State(state): State<AppState>) -> Response {
    ws.max_message_size(MAX_FRAME_BYTES)
        .max_frame_size(MAX_FRAME_BYTES)
        .on_upgrade(move |socket| page(socket, state))
}

async fn page(mut socket: WebSocket, state: AppState) {
    // Subscribe before saying hello, so no update falls between the two.
    let mut updates = state.out.subscribe();
    let (reply, mut replies) = mpsc::unbounded_channel();
    if !state.send(Command::Hello(reply)) {
        return;
    }
    loop {
        let outgoing = tokio::select! {
            incoming = socket.recv() => match incoming {
                Some(Ok(Message::Text(text))) => match ClientMessage::parse(text.as_str()) {
                    Ok(message) => {
                        if !state.send(Command::Message(message, Instant::now())) {
                            return;
                        }
                        continue;
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
                // Fell behind: the skipped updates are stale anyway.
                Err(broadcast::error::RecvError::Lagged(_)) => continue,
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
