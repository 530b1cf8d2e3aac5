//! The editor thread: owns the workspace and its `EditSession`, reads commands between solver
//! steps and broadcasts every iterate. Commands that arrive while a solve runs are all read
//! before the next step, so a newer drag replaces a stale one at once.

use crate::protocol::{
    error_message, mesh_message, state_message, warning_message, ClientMessage, Remakes, UpdateInfo,
};
use crate::source::{save_dir, Source};
use honeycomb::export::{export, write_structure, ExportOptions, Model, Units};
use honeycomb::interactive::{EditSession, SessionOptions, Watch, Workspace};
use honeycomb::mesh::{replace_folder, write_mesh};
use honeycomb::report::Report;
use honeycomb::Result;
use serde_json::{json, Value};
use std::path::PathBuf;
use std::sync::mpsc::{Receiver, TryRecvError};
use std::sync::Arc;
use std::time::Instant;
use tokio::sync::{broadcast, mpsc};

pub enum Command {
    /// A parsed message from a page, with the moment it was read.
    Message(ClientMessage, Instant, Page),
    /// A new page (its number): send it the mesh and the current state.
    Hello(u64, mpsc::UnboundedSender<Arc<str>>),
    /// A download of `file` (one of `protocol::DOWNLOADS`) made from the current state, one
    /// model unit standing for `Units`.
    Download(String, Units, tokio::sync::oneshot::Sender<Download>),
}

/// A download's bytes, or why there are none.
pub enum Download {
    Bytes(Vec<u8>),
    /// The current state is not a honeycomb (a fabricator must not cut it).
    NotHoneycomb(String),
    Failed(String),
}

/// The page a message came from: its number (pages number their own gestures) and where its
/// own replies go (an error is news to that page only).
pub struct Page {
    pub number: u64,
    pub reply: mpsc::UnboundedSender<Arc<str>>,
}

impl Page {
    fn tell(&self, message: Value) {
        tell(&self.reply, message);
    }
}

/// Sends `message` to one page.
fn tell(reply: &mpsc::UnboundedSender<Arc<str>>, message: Value) {
    // A page that has gone needs no answer.
    let _ = reply.send(Arc::from(message.to_string()));
}

pub struct Editor {
    pub commands: Receiver<Command>,
    pub out: broadcast::Sender<Arc<str>>,
    pub save_root: PathBuf,
    pub options: SessionOptions,
}

/// What the editor edits: the workspace, how the page names it, and the input it came from
/// (which a remake makes again).
struct Current {
    /// Shared with the session made from it.
    ws: Arc<Workspace>,
    label: String,
    source: Source,
    thickness: Option<f64>,
    /// What its variant is judged by, measured again after every edit.
    watch: Option<Watch>,
}

impl Current {
    fn remakes(&self) -> Remakes {
        match &self.source {
            Source::Surface { cells, .. } => Remakes {
                cells: Some(*cells),
                thickness: true,
            },
            Source::Demo { .. } => Remakes {
                cells: None,
                thickness: true,
            },
            Source::Structure(_) => Remakes::default(),
        }
    }
}

/// How an editing run ended.
enum Next {
    Load(Box<Current>),
    Stop,
}

struct Progress {
    seq: u64,
    stroke: Option<u64>,
    iteration: usize,
    edit_start: Instant,
    step_ms: f64,
}

impl Progress {
    fn new() -> Progress {
        Progress {
            seq: 0,
            stroke: None,
            iteration: 0,
            edit_start: Instant::now(),
            step_ms: 0.0,
        }
    }
}

impl Editor {
    /// Runs until every sender of commands is gone. `ready` hears whether the first session
    /// could be set up.
    pub fn run(
        self,
        first: Workspace,
        watch: Option<Watch>,
        source: Source,
        thickness: Option<f64>,
        ready: std::sync::mpsc::Sender<Result<()>>,
    ) {
        let mut ready = Some(ready);
        let mut current = Current {
            ws: Arc::new(first),
            label: source.label(),
            source,
            thickness,
            watch,
        };
        // The workspace before a load, to go back to when the loaded one cannot be solved.
        let mut previous: Option<Current> = None;
        loop {
            let outcome = match EditSession::new(Arc::clone(&current.ws), self.options.clone()) {
                Ok(mut session) => {
                    match ready.take() {
                        // Serving starts now: every page hears the mesh and the state when it
                        // says hello, once.
                        Some(r) => {
                            let _ = r.send(Ok(()));
                        }
                        // A load or a remake: the pages already there hear the new ones.
                        None => {
                            self.broadcast(self.mesh(&current));
                            self.broadcast(self.state(&session, &current, &Progress::new()));
                        }
                    }
                    match self.edit(&mut session, &current) {
                        Next::Load(next) => Ok(next),
                        Next::Stop => return,
                    }
                }
                Err(e) => Err(e),
            };
            match outcome {
                Ok(next) => previous = Some(std::mem::replace(&mut current, *next)),
                Err(e) => {
                    if let Some(r) = ready.take() {
                        let _ = r.send(Err(e));
                        return;
                    }
                    self.broadcast(error_message(&format!("load failed: {e}")));
                    match previous.take() {
                        Some(back) => current = back,
                        None => return,
                    }
                }
            }
        }
    }

    fn mesh(&self, current: &Current) -> Value {
        mesh_message(
            &current.ws,
            &current.label,
            current.remakes(),
            current.watch.as_ref(),
        )
    }

    fn broadcast(&self, message: Value) {
        // No page connected is fine: the state is kept for the next one.
        let _ = self.out.send(Arc::from(message.to_string()));
    }

    fn state(&self, session: &EditSession, current: &Current, p: &Progress) -> Value {
        let info = UpdateInfo {
            seq: p.seq,
            stroke: p.stroke,
            iteration: p.iteration,
            done: !session.solving(),
            step_ms: p.step_ms,
            edit_ms: p.edit_start.elapsed().as_secs_f64() * 1e3,
            undo_page: session.undo_author(),
            redo_page: session.redo_author(),
        };
        let view = session.view();
        // Measured once an edit's solve has ended: the light share samples every cell.
        let watched = (current.watch.as_ref())
            .filter(|_| info.done)
            .map(|w| w.measure(&view.honeycomb, &current.ws.conn, &current.ws.model_surface));
        state_message(&view, &info, watched.as_ref())
    }

    fn edit(&self, session: &mut EditSession, current: &Current) -> Next {
        let mut p = Progress::new();
        loop {
            let command = if session.solving() {
                match self.commands.try_recv() {
                    Ok(c) => Some(c),
                    Err(TryRecvError::Empty) => None,
                    Err(TryRecvError::Disconnected) => return Next::Stop,
                }
            } else {
                match self.commands.recv() {
                    Ok(c) => Some(c),
                    Err(_) => return Next::Stop,
                }
            };
            if let Some(command) = command {
                match command {
                    Command::Hello(number, reply) => {
                        // The page's number first: its undo button follows the states'
                        // `undo_page`.
                        tell(&reply, json!({ "type": "hello", "page": number }));
                        tell(&reply, self.mesh(current));
                        tell(&reply, self.state(session, current, &p));
                    }
                    Command::Download(file, units, reply) => {
                        let _ = reply.send(download(session, &current.ws, &file, units));
                    }
                    Command::Message(message, at, page) => {
                        if let Some(next) = self.handle(session, current, message, at, page, &mut p)
                        {
                            return next;
                        }
                    }
                }
                continue;
            }
            // No command waiting: one step of the running solve.
            let t = Instant::now();
            let step = session.step();
            p.step_ms = t.elapsed().as_secs_f64() * 1e3;
            match step {
                Ok(Some(_)) => p.iteration += 1,
                Ok(None) => {}
                Err(e) => {
                    session.cancel();
                    self.broadcast(error_message(&format!("the solve stopped: {e}")));
                }
            }
            p.seq += 1;
            self.broadcast(self.state(session, current, &p));
        }
    }

    /// Handles one message; `Some` ends this session (a load).
    fn handle(
        &self,
        session: &mut EditSession,
        current: &Current,
        message: ClientMessage,
        at: Instant,
        page: Page,
        p: &mut Progress,
    ) -> Option<Next> {
        let instant = |p: &mut Progress, stroke| {
            p.stroke = stroke;
            p.iteration = 0;
            p.edit_start = at;
            p.step_ms = 0.0;
        };
        if let Some((edit, stroke)) = message.edit() {
            let key = stroke.map(|s| gesture(page.number, s));
            match session.apply_by(edit, key, page.number) {
                Ok(applied) => {
                    if let Some(w) = applied.warning {
                        page.tell(warning_message(&w));
                    }
                    instant(p, stroke);
                    if !session.solving() {
                        // A slide: nothing to solve, show it now.
                        p.seq += 1;
                        self.broadcast(self.state(session, current, p));
                    }
                }
                Err(e) => page.tell(error_message(&e.to_string())),
            }
            return None;
        }
        match message {
            ClientMessage::Undo {} | ClientMessage::Redo {} | ClientMessage::Cancel {} => {
                // A page takes back (or brings back) only its own gestures, newest first: a new
                // page has nothing to undo, whatever the others did.
                let refusal = match message {
                    ClientMessage::Undo {} => own(session.undo_author(), page.number, "undo")
                        .map(|()| session.undo())
                        .err(),
                    ClientMessage::Redo {} => own(session.redo_author(), page.number, "redo")
                        .map(|()| session.redo())
                        .err(),
                    _ => {
                        session.cancel();
                        None
                    }
                };
                if let Some(why) = refusal {
                    page.tell(error_message(&why));
                }
                instant(p, None);
                p.seq += 1;
                self.broadcast(self.state(session, current, p));
            }
            ClientMessage::Save { name } => match self.save(session, &current.ws, &name) {
                Ok(dir) => self.broadcast(json!({
                    "type": "saved", "name": name, "dir": dir.display().to_string()
                })),
                Err(e) => page.tell(error_message(&format!("save failed: {e}"))),
            },
            ClientMessage::Load { name } => {
                let loaded = save_dir(&self.save_root, &name).and_then(|dir| {
                    let source = Source::Structure(dir);
                    Ok((source.workspace(None)?, source))
                });
                match loaded {
                    Ok((ws, source)) => {
                        return Some(Next::Load(Box::new(Current {
                            ws: Arc::new(ws),
                            label: name,
                            source,
                            thickness: None,
                            watch: None,
                        })))
                    }
                    Err(e) => page.tell(error_message(&format!("load failed: {e}"))),
                }
            }
            ClientMessage::Remake { cells, thickness } => match remake(current, cells, thickness) {
                Ok((next, notes)) => {
                    if !notes.is_empty() {
                        page.tell(warning_message(&notes.join("; ")));
                    }
                    return Some(Next::Load(Box::new(next)));
                }
                Err(e) => page.tell(error_message(&format!("remake failed: {e}"))),
            },
            // The edits, handled above.
            ClientMessage::DragVertex { .. }
            | ClientMessage::Slide { .. }
            | ClientMessage::DragAxis { .. } => {}
        }
        None
    }

    /// Writes the current structure, its surface and its measures into `root/name`, which
    /// appears whole or not at all (a failed save leaves the earlier one as it was), and only
    /// once it loads as `load` will load it: a save that could not be loaded is no save.
    fn save(&self, session: &EditSession, ws: &Workspace, name: &str) -> Result<PathBuf> {
        let dir = save_dir(&self.save_root, name)?;
        let view = session.view();
        replace_folder(&dir, |folder| {
            write_mesh(
                &folder.join("surface.obj"),
                &ws.model_surface.mesh_for_export(),
            )?;
            write_structure(
                folder,
                &view.honeycomb,
                &json!({ "measures": view.measures }),
            )?;
            Source::Structure(folder.to_path_buf())
                .workspace(None)
                .map(|_| ())
                .map_err(|e| {
                    honeycomb::Error::Parameter(format!("the structure would not load again: {e}"))
                })
        })?;
        Ok(dir)
    }
}

/// The session's key for gesture `stroke` of page `page`: pages number their gestures from 1
/// each, and two pages' gesture 1 must not share an undo step. Pages count up from 0 and
/// gestures stay far below 2^40 (one a millisecond for 30 years).
fn gesture(page: u64, stroke: u64) -> u64 {
    (page << 40) ^ stroke
}

/// Whether `page` may undo (redo) the gesture of `author`: only its own.
fn own(author: Option<u64>, page: u64, what: &str) -> std::result::Result<(), String> {
    match author {
        Some(a) if a == page => Ok(()),
        Some(_) => Err(format!(
            "nothing of this page's to {what}: the newest gesture is another page's (a page \
             takes back only its own gestures, newest first)"
        )),
        None => Err(format!("nothing to {what}")),
    }
}

/// The input made again with `cells` and `thickness` (each as it is now when left out), and
/// the pipeline's notes. The options are checked as the CLI checks them before anything is
/// solved.
fn remake(
    current: &Current,
    cells: Option<usize>,
    thickness: Option<f64>,
) -> Result<(Current, Vec<String>)> {
    use honeycomb::Error;
    if cells.is_none() && thickness.is_none() {
        return Err(Error::Parameter("give cells or thickness (or both)".into()));
    }
    if let Some(t) = thickness {
        honeycomb::error::check_positive_length("thickness", t)?;
    }
    let source = match (&current.source, cells) {
        (
            Source::Surface {
                path,
                options,
                even_cells,
                ..
            },
            Some(cells),
        ) => Source::Surface {
            path: path.clone(),
            cells,
            options: options.clone(),
            even_cells: *even_cells,
        },
        (Source::Structure(_), _) => {
            return Err(Error::Parameter(
                "a structure directory (or a save) is edited as it was made: thickness and \
                 cells are for a design surface (and thickness for the demo)"
                    .into(),
            ))
        }
        (Source::Demo { .. }, Some(_)) => {
            return Err(Error::Parameter(
                "cells: the demo is a built-in mesh; a cell count is for a design surface \
                 (serve SURFACE.obj)"
                    .into(),
            ))
        }
        (source, None) => source.clone(),
    };
    let thickness = thickness.or(current.thickness);
    let crate::source::Made { ws, notes, watch } = source.made(thickness)?;
    let next = Current {
        ws: Arc::new(ws),
        label: source.label(),
        source,
        thickness,
        watch,
    };
    Ok((next, notes))
}

/// `file` of `honeycomb export`, made from the current state in a temporary folder; refused
/// when the state is not a honeycomb (mid-solve, or an edit that broke it).
fn download(session: &EditSession, ws: &Workspace, file: &str, units: Units) -> Download {
    let format = match crate::protocol::download(file) {
        Ok((_, format)) => format,
        Err(e) => return Download::Failed(e),
    };
    let view = session.view();
    if session.solving() || !Report::within_tolerances(&view.measures) {
        return Download::NotHoneycomb(format!(
            "the current state is not a honeycomb ({}{}): nothing to download; undo the last \
             edit or wait for the solve",
            Report::tolerance_summary(&view.measures, false),
            if session.solving() {
                ", still solving"
            } else {
                ""
            }
        ));
    }
    let made = Model::new(
        view.honeycomb,
        Some(ws.model_surface.mesh_for_export()),
        units,
    )
    .and_then(|model| {
        let folder = TempFolder::new()?;
        let out = folder.0.join("export");
        let options = ExportOptions {
            formats: vec![format],
            units,
            ..ExportOptions::default()
        };
        export(&model, &options, &out, &[])?;
        let path = out.join(file);
        std::fs::read(&path).map_err(|source| honeycomb::Error::Io { path, source })
    });
    match made {
        Ok(bytes) => Download::Bytes(bytes),
        Err(e) => Download::Failed(format!("{file}: {e}")),
    }
}

/// A folder of its own under the system's temporary folder, removed when dropped.
struct TempFolder(PathBuf);

impl TempFolder {
    fn new() -> Result<TempFolder> {
        static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let dir =
            std::env::temp_dir().join(format!("honeycomb-download-{}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        match std::fs::create_dir_all(&dir) {
            Ok(()) => Ok(TempFolder(dir)),
            Err(source) => Err(honeycomb::Error::Io { path: dir, source }),
        }
    }
}

impl Drop for TempFolder {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
