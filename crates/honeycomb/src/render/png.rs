//! A small RGB canvas (scanline polygon fill, lines) and a PNG encoder with stored (uncompressed)
//! deflate blocks: no dependency, and pictures are for looking at, not for archiving.

pub struct Canvas {
    width: u32,
    height: u32,
    pixels: Vec<[u8; 3]>,
}

impl Canvas {
    pub fn new(width: u32, height: u32) -> Canvas {
        Canvas {
            width,
            height,
            pixels: vec![[255, 255, 255]; (width * height) as usize],
        }
    }

    #[cfg(test)]
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        self.pixels[(y * self.width + x) as usize]
    }

    fn blend(&mut self, x: i64, y: i64, (r, g, b): (u8, u8, u8), alpha: f64) {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            return;
        }
        let p = &mut self.pixels[(y as u32 * self.width + x as u32) as usize];
        let mix = |old: u8, new: u8| (old as f64 + (new as f64 - old as f64) * alpha).round() as u8;
        *p = [mix(p[0], r), mix(p[1], g), mix(p[2], b)];
    }

    /// Even-odd fill, sampled at pixel centres.
    pub fn fill_polygon(&mut self, points: &[(f64, f64)], color: (u8, u8, u8), alpha: f64) {
        if points.len() < 3 {
            return;
        }
        let (y0, y1) = points.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
            (lo.min(p.1), hi.max(p.1))
        });
        let (y0, y1) = (
            y0.floor().max(0.0) as i64,
            y1.ceil().min(self.height as f64) as i64,
        );
        let mut xs = Vec::new();
        for y in y0..y1 {
            let yc = y as f64 + 0.5;
            xs.clear();
            for k in 0..points.len() {
                let (a, b) = (points[k], points[(k + 1) % points.len()]);
                if (a.1 <= yc) != (b.1 <= yc) {
                    xs.push(a.0 + (yc - a.1) * (b.0 - a.0) / (b.1 - a.1));
                }
            }
            xs.sort_by(f64::total_cmp);
            for pair in xs.chunks_exact(2) {
                let (from, to) = (
                    (pair[0] - 0.5).ceil() as i64,
                    (pair[1] - 0.5).floor() as i64,
                );
                for x in from.max(0)..=to.min(self.width as i64 - 1) {
                    self.blend(x, y, color, alpha);
                }
            }
        }
    }

    /// A one-pixel line.
    pub fn line(&mut self, a: (f64, f64), b: (f64, f64), color: (u8, u8, u8)) {
        let steps = (b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil().max(1.0) as usize;
        for i in 0..=steps {
            let t = i as f64 / steps as f64;
            let (x, y) = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
            self.blend(x.floor() as i64, y.floor() as i64, color, 1.0);
        }
    }

    pub fn encode(&self) -> Vec<u8> {
        let mut raw = Vec::with_capacity(self.pixels.len() * 3 + self.height as usize);
        for row in self.pixels.chunks(self.width as usize) {
            raw.push(0); // filter: none
            for p in row {
                raw.extend_from_slice(p);
            }
        }
        let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
        let mut ihdr = Vec::new();
        ihdr.extend_from_slice(&self.width.to_be_bytes());
        ihdr.extend_from_slice(&self.height.to_be_bytes());
        ihdr.extend_from_slice(&[8, 2, 0, 0, 0]); // 8-bit RGB
        chunk(&mut out, b"IHDR", &ihdr);
        chunk(&mut out, b"IDAT", &zlib_stored(&raw));
        chunk(&mut out, b"IEND", &[]);
        out
    }
}

fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    out.extend_from_slice(&(data.len() as u32).to_be_bytes());
    let start = out.len();
    out.extend_from_slice(kind);
    out.extend_from_slice(data);
    let crc = crc32(&out[start..]);
    out.extend_from_slice(&crc.to_be_bytes());
}

/// A zlib stream of stored deflate blocks.
fn zlib_stored(data: &[u8]) -> Vec<u8> {
    let mut out = vec![0x78, 0x01];
    let blocks: Vec<&[u8]> = data.chunks(65_535).collect();
    for (i, block) in blocks.iter().enumerate() {
        out.push(u8::from(i + 1 == blocks.len()));
        let len = block.len() as u16;
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&(!len).to_le_bytes());
        out.extend_from_slice(block);
    }
    if blocks.is_empty() {
        out.extend_from_slice(&[1, 0, 0, 0xff, 0xff]);
    }
    let (mut a, mut b) = (1u32, 0u32);
    for &byte in data {
        a = (a + byte as u32) % 65_521;
        b = (b + a) % 65_521;
    }
    out.extend_from_slice(&((b << 16) | a).to_be_bytes());
    out
}

fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in data {
        crc ^= byte as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc_and_a_filled_square() {
        // The CRC of "IEND" is the well-known trailer of every PNG.
        assert_eq!(crc32(b"IEND"), 0xAE42_6082);
        let mut c = Canvas::new(10, 10);
        c.fill_polygon(
            &[(2.0, 2.0), (8.0, 2.0), (8.0, 8.0), (2.0, 8.0)],
            (255, 0, 0),
            1.0,
        );
        assert_eq!(c.pixel(5, 5), [255, 0, 0]);
        assert_eq!(c.pixel(1, 5), [255, 255, 255]);
        assert_eq!(c.pixel(8, 5), [255, 255, 255]);
        let png = c.encode();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        assert_eq!(&png[png.len() - 8..png.len() - 4], b"IEND");
    }
}
