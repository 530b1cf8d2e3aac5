//! The editor's latency, measured the way a page sees it: a WebSocket client sends axis drags
//! (mode iii) and slides (mode ii) and times each until the updated geometry arrives.

use crate::{start, ServeOptions, Source};
use honeycomb::{Error, Result, Vec3};
use serde::Serialize;
use serde_json::{json, Value};
use std::net::TcpStream;
use std::time::Instant;
use tungstenite::{connect, stream::MaybeTlsStream, Message, WebSocket};

#[derive(Debug, Serialize)]
pub struct Latency {
    pub vertices: usize,
    pub drags: usize,
    /// Drag message sent -> first updated geometry received (one solver step), milliseconds.
    pub first_update_median_ms: f64,
    pub first_update_p90_ms: f64,
    /// Drag message sent -> the edit's last update (converged or out of steps).
    pub done_median_ms: f64,
    pub steps_per_drag: f64,
    /// Solver step alone (server side), median.
    pub step_median_ms: f64,
    /// Slide message sent -> updated geometry (no optimization).
    pub slide_median_ms: f64,
    /// omega_max after the last drag, from the panel's figures (realized geometry).
    pub omega_max_deg: f64,
}

pub struct Client {
    socket: WebSocket<MaybeTlsStream<TcpStream>>,
}

impl Client {
    pub fn connect(url: &str) -> Result<Client> {
        let (socket, _) =
            connect(url).map_err(|e| Error::Parameter(format!("cannot connect to {url}: {e}")))?;
        // A silent server is a failure, not a hang.
        if let MaybeTlsStream::Plain(s) = socket.get_ref() {
            let _ = s.set_read_timeout(Some(std::time::Duration::from_secs(60)));
        }
        Ok(Client { socket })
    }

    pub fn send(&mut self, message: &Value) -> Result<()> {
        self.send_text(&message.to_string())
    }

    pub fn send_text(&mut self, text: &str) -> Result<()> {
        self.socket
            .send(Message::text(text))
            .map_err(|e| Error::Parameter(format!("send failed: {e}")))
    }

    pub fn send_binary(&mut self, bytes: &[u8]) -> Result<()> {
        self.socket
            .send(Message::binary(bytes.to_vec()))
            .map_err(|e| Error::Parameter(format!("send failed: {e}")))
    }

    /// The next JSON message from the server.
    pub fn receive(&mut self) -> Result<Value> {
        loop {
            match self.socket.read() {
                Ok(Message::Text(t)) => {
                    return serde_json::from_str(t.as_str())
                        .map_err(|e| Error::Parameter(format!("bad JSON from the server: {e}")))
                }
                Ok(_) => continue,
                Err(e) => return Err(Error::Parameter(format!("connection lost: {e}"))),
            }
        }
    }

    /// Messages until one of `kind` for which `accept` holds; an error message from the server
    /// while waiting for something else ends the wait.
    pub fn until(&mut self, kind: &str, accept: impl Fn(&Value) -> bool) -> Result<Value> {
        loop {
            let m = self.receive()?;
            if m["type"] == kind && accept(&m) {
                return Ok(m);
            }
            if m["type"] == "error" {
                return Err(Error::Parameter(format!(
                    "the editor says: {}",
                    m["message"]
                )));
            }
        }
    }
}

fn point(flat: &Value, v: usize) -> Vec3 {
    let c = |k: usize| flat[3 * v + k].as_f64().unwrap_or(f64::NAN);
    Vec3::new(c(0), c(1), c(2))
}

fn median(v: &mut [f64]) -> f64 {
    percentile(v, 0.5)
}

fn percentile(v: &mut [f64], q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(((v.len() as f64 - 1.0) * q).round() as usize)
        .copied()
        .unwrap_or(f64::NAN)
}

/// Starts an editor on `source` and times `drags` axis drags and as many slides.
pub fn measure(source: &Source, drags: usize) -> Result<Latency> {
    let save_root = std::env::temp_dir().join(format!("honeycomb-latency-{}", std::process::id()));
    let server = start(
        source,
        ServeOptions {
            port: 0,
            save_root,
            ..ServeOptions::default()
        },
    )?;
    let result = drive(&format!("ws://{}/ws", server.addr), drags);
    server.stop();
    result
}

fn drive(url: &str, drags: usize) -> Result<Latency> {
    let mut client = Client::connect(url)?;
    let mesh = client.until("mesh", |_| true)?;
    let state = client.until("state", |_| true)?;
    let nv = mesh["vertices"].as_u64().unwrap_or(0) as usize;
    let base: Vec<Vec3> = (0..nv).map(|v| point(&state["base"], v)).collect();
    let centroid = base.iter().fold(Vec3::ZERO, |s, &p| s + p) / nv.max(1) as f64;
    let vertex = (0..nv)
        .min_by(|&a, &b| {
            (base[a] - centroid)
                .norm()
                .total_cmp(&(base[b] - centroid).norm())
        })
        .ok_or_else(|| Error::Parameter("the editor sent an empty mesh".into()))?;
    let axis = (point(&state["offset"], vertex) - base[vertex]).normalized();
    let tangent = axis.any_orthogonal().normalized();

    let (mut first, mut done, mut steps, mut step_ms, mut slides) =
        (Vec::new(), Vec::new(), 0usize, Vec::new(), Vec::new());
    let mut omega = f64::NAN;
    for k in 0..drags {
        // Five degrees one way, then the other: the axis rocks about where it started.
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        let direction = (axis + tangent * (sign * 0.0875)).normalized();
        let stroke = 2 * k as u64 + 1;
        let t = Instant::now();
        client.send(&json!({
            "type": "drag_axis", "vertex": vertex, "direction": direction.to_array(),
            "radius": 3, "stroke": stroke,
        }))?;
        let mine = |m: &Value| m["stroke"] == stroke;
        let m = client.until("state", |m| mine(m) && m["iteration"].as_u64() >= Some(1))?;
        first.push(t.elapsed().as_secs_f64() * 1e3);
        step_ms.push(m["step_ms"].as_f64().unwrap_or(f64::NAN));
        let m = if m["done"] == true {
            m
        } else {
            client.until("state", |m| mine(m) && m["done"] == true)?
        };
        done.push(t.elapsed().as_secs_f64() * 1e3);
        steps += m["iteration"].as_u64().unwrap_or(0) as usize;
        omega = m["measures"]["omega_max_deg"].as_f64().unwrap_or(f64::NAN);

        let stroke = stroke + 1;
        let t = Instant::now();
        client.send(&json!({
            "type": "slide", "vertex": vertex, "distance": 0.0, "stroke": stroke,
        }))?;
        client.until("state", |m| m["stroke"] == stroke)?;
        slides.push(t.elapsed().as_secs_f64() * 1e3);
    }
    Ok(Latency {
        vertices: nv,
        drags,
        first_update_median_ms: median(&mut first),
        first_update_p90_ms: percentile(&mut first, 0.9),
        done_median_ms: median(&mut done),
        steps_per_drag: steps as f64 / drags.max(1) as f64,
        step_median_ms: median(&mut step_ms),
        slide_median_ms: median(&mut slides),
        omega_max_deg: omega,
    })
}
