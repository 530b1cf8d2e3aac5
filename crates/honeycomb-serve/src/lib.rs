//! `honeycomb serve`: the interactive editor in the browser (paper section 4, Fig. 10). A thin
//! front over the library's `EditSession`: one editor thread solves, a small tokio runtime
//! serves the page and the WebSocket.

mod assets;
mod editor;
pub mod latency;
pub mod protocol;
mod server;
mod source;

pub use source::Source;

use editor::Editor;
use honeycomb::interactive::SessionOptions;
use honeycomb::{Error, Result};
use server::AppState;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use tokio::sync::{broadcast, oneshot};

#[derive(Clone, Debug)]
pub struct ServeOptions {
    /// 127.0.0.1 unless the user asks otherwise.
    pub host: std::net::IpAddr,
    /// 0: any free port.
    pub port: u16,
    /// Where the page's saves go (one folder per name).
    pub save_root: PathBuf,
    pub session: SessionOptions,
    /// Distance of M' from M (model units); `None`: 0.3 mean edge lengths.
    pub thickness: Option<f64>,
}

impl Default for ServeOptions {
    fn default() -> Self {
        ServeOptions {
            host: [127, 0, 0, 1].into(),
            port: 8080,
            save_root: PathBuf::from("honeycomb-saves"),
            session: SessionOptions::default(),
            thickness: None,
        }
    }
}

/// A running editor.
pub struct Server {
    pub addr: SocketAddr,
    /// What the pipeline changed on the way to the first honeycomb, for the front to show.
    pub notes: Vec<String>,
    stop: Option<oneshot::Sender<()>>,
    http: Option<std::thread::JoinHandle<()>>,
}

impl Server {
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// Blocks until the server stops (Ctrl-C).
    pub fn wait(mut self) {
        if let Some(h) = self.http.take() {
            let _ = h.join();
        }
    }

    /// Stops serving and waits for it.
    pub fn stop(mut self) {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
        if let Some(h) = self.http.take() {
            let _ = h.join();
        }
    }
}

/// Builds the workspace, solves it into a honeycomb, binds the port and starts serving. Errors
/// (a bad input, a taken port) come back here, before anything is served.
pub fn start(source: &Source, options: ServeOptions) -> Result<Server> {
    let source::Made { ws, notes, watch } = source.made(options.thickness)?;
    let listener = std::net::TcpListener::bind((options.host, options.port)).map_err(|e| {
        Error::Parameter(format!(
            "cannot listen on {}:{}: {e}",
            options.host, options.port
        ))
    })?;
    let addr = listener
        .local_addr()
        .map_err(|e| Error::Parameter(e.to_string()))?;
    listener
        .set_nonblocking(true)
        .map_err(|e| Error::Parameter(e.to_string()))?;

    // Bounded: a page that sends faster than the editor works gets "busy" replies instead of
    // a queue that delays every page and grows without limit.
    let (commands_tx, commands) = std::sync::mpsc::sync_channel(server::COMMAND_QUEUE);
    let (out, _) = broadcast::channel(16);
    let (ready_tx, ready) = std::sync::mpsc::channel();
    let editor = Editor {
        commands,
        out: out.clone(),
        save_root: options.save_root.clone(),
        options: options.session.clone(),
    };
    let (first, thickness) = (source.clone(), options.thickness);
    std::thread::Builder::new()
        .name("editor".into())
        .spawn(move || editor.run(ws, watch, first, thickness, ready_tx))
        .map_err(|e| Error::Parameter(format!("cannot start the editor thread: {e}")))?;
    ready
        .recv()
        .map_err(|_| Error::Solver("the editor stopped while starting".into()))??;

    let state = AppState {
        commands: Arc::new(Mutex::new(commands_tx)),
        out,
        loopback_only: options.host.is_loopback(),
    };
    let (stop_tx, stop_rx) = oneshot::channel::<()>();
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .enable_all()
        .build()
        .map_err(|e| Error::Parameter(format!("cannot start the server runtime: {e}")))?;
    let http = std::thread::Builder::new()
        .name("http".into())
        .spawn(move || {
            runtime.block_on(async move {
                let Ok(listener) = tokio::net::TcpListener::from_std(listener) else {
                    return;
                };
                let shutdown = async move {
                    tokio::select! {
                        _ = stop_rx => {}
                        _ = tokio::signal::ctrl_c() => {}
                    }
                };
                let _ = axum::serve(listener, server::router(state))
                    .with_graceful_shutdown(shutdown)
                    .await;
            });
        })
        .map_err(|e| Error::Parameter(format!("cannot start the server thread: {e}")))?;
    Ok(Server {
        addr,
        notes,
        stop: Some(stop_tx),
        http: Some(http),
    })
}
