//! The editor thread: owns the workspace and its `EditSession`, reads commands between solver
//! steps and broadcasts every iterate. Commands that arrive while a solve runs are all read
//! before the next step, so a newer drag replaces a stale one at once.

use crate::protocol::{error_message, mesh_message, state_message, ClientMessage, UpdateInfo};
use crate::source::{save_dir, Source};
use honeycomb::export::write_structure;
use honeycomb::interactive::{EditSession, SessionOptions, Workspace};
use honeycomb::mesh::{replace_folder, write_mesh};
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
    /// A new page: send it the mesh and the current state.
    Hello(mpsc::UnboundedSender<Arc<str>>),
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
    pub thickness: Option<f64>,
}

/// How an editing run ended.
enum Next {
    Load(Box<Workspace>, String),
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
    pub fn run(self, first: Workspace, label: String, ready: std::sync::mpsc::Sender<Result<()>>) {
        let mut ready = Some(ready);
        let (mut ws, mut label) = (first, label);
        // The workspace before a load, to go back to when the loaded one cannot be solved.
        let mut previous: Option<(Workspace, String)> = None;
        loop {
            let outcome = match EditSession::new(&ws, self.options.clone()) {
                Ok(mut session) => {
                    if let Some(r) = ready.take() {
                        let _ = r.send(Ok(()));
                    }
                    self.broadcast(mesh_message(&ws, &label));
                    self.broadcast(self.state(&session, &Progress::new()));
                    match self.edit(&mut session, &ws, &label) {
                        Next::Load(next, next_label) => Ok((next, next_label)),
                        Next::Stop => return,
                    }
                }
                Err(e) => Err(e),
            };
            match outcome {
                Ok((next, next_label)) => {
                    let old = std::mem::replace(&mut ws, *next);
                    previous = Some((old, std::mem::replace(&mut label, next_label)));
                }
                Err(e) => {
                    if let Some(r) = ready.take() {
                        let _ = r.send(Err(e));
                        return;
                    }
                    self.broadcast(error_message(&format!("load failed: {e}")));
                    match previous.take() {
                        Some(back) => (ws, label) = back,
                        None => return,
                    }
                }
            }
        }
    }

    fn broadcast(&self, message: Value) {
        // No page connected is fine: the state is kept for the next one.
        let _ = self.out.send(Arc::from(message.to_string()));
    }

    fn state(&self, session: &EditSession, p: &Progress) -> Value {
        let info = UpdateInfo {
            seq: p.seq,
            stroke: p.stroke,
            iteration: p.iteration,
            done: !session.solving(),
            step_ms: p.step_ms,
            edit_ms: p.edit_start.elapsed().as_secs_f64() * 1e3,
            can_undo: session.can_undo(),
            can_redo: session.can_redo(),
        };
        state_message(&session.view(), &info)
    }

    fn edit(&self, session: &mut EditSession, ws: &Workspace, label: &str) -> Next {
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
                    Command::Hello(reply) => {
                        tell(&reply, mesh_message(ws, label));
                        tell(&reply, self.state(session, &p));
                    }
                    Command::Message(message, at, page) => {
                        if let Some(next) = self.handle(session, ws, message, at, page, &mut p) {
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
            self.broadcast(self.state(session, &p));
        }
    }

    /// Handles one message; `Some` ends this session (a load).
    fn handle(
        &self,
        session: &mut EditSession,
        ws: &Workspace,
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
            match session.apply(edit, stroke.map(|s| gesture(page.number, s))) {
                Ok(()) => {
                    instant(p, stroke);
                    if !session.solving() {
                        // A slide: nothing to solve, show it now.
                        p.seq += 1;
                        self.broadcast(self.state(session, p));
                    }
                }
                Err(e) => page.tell(error_message(&e.to_string())),
            }
            return None;
        }
        match message {
            ClientMessage::Undo {} | ClientMessage::Redo {} | ClientMessage::Cancel {} => {
                let changed = match message {
                    ClientMessage::Undo {} => session.undo(),
                    ClientMessage::Redo {} => session.redo(),
                    _ => {
                        session.cancel();
                        true
                    }
                };
                if !changed {
                    page.tell(error_message("nothing to undo or redo"));
                }
                instant(p, None);
                p.seq += 1;
                self.broadcast(self.state(session, p));
            }
            ClientMessage::Save { name } => match self.save(session, ws, &name) {
                Ok(dir) => self.broadcast(json!({
                    "type": "saved", "name": name, "dir": dir.display().to_string()
                })),
                Err(e) => page.tell(error_message(&format!("save failed: {e}"))),
            },
            ClientMessage::Load { name } => {
                let loaded = save_dir(&self.save_root, &name)
                    .and_then(|dir| Source::Structure(dir).workspace(self.thickness));
                match loaded {
                    Ok(next) => return Some(Next::Load(Box::new(next), name)),
                    Err(e) => page.tell(error_message(&format!("load failed: {e}"))),
                }
            }
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
