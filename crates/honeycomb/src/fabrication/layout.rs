//! Panels laid out on sheets: rows of panels, tallest first, each panel a gap apart from the
//! next and from the sheet's edge (shelf packing). Panels keep their lie (M's edge along x)
//! unless only a quarter turn makes one fit.

use super::panel::{bounds, Panel, Point};
use crate::error::{rounded, Error, Result};

/// Sheet size (model units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sheet {
    pub width: f64,
    pub height: f64,
}

/// A panel placed on a sheet: its points map by `place`.
#[derive(Clone, Debug)]
pub struct Placed {
    /// Index into the panels laid out.
    pub panel: usize,
    pub sheet: usize,
    /// Turned a quarter turn anticlockwise before it was moved.
    pub turned: bool,
    /// Where the panel's lower-left bound lands.
    pub offset: Point,
    /// The panel's own lower-left bound (before the move).
    origin: Point,
}

impl Placed {
    /// A point of the panel in sheet coordinates.
    pub fn place(&self, p: Point) -> Point {
        let q = if self.turned { [-p[1], p[0]] } else { p };
        [
            q[0] - self.origin[0] + self.offset[0],
            q[1] - self.origin[1] + self.offset[1],
        ]
    }
}

#[derive(Clone, Debug)]
pub struct Layout {
    pub sheet: Sheet,
    pub gap: f64,
    pub sheets: usize,
    /// One per panel, in the panels' order.
    pub placed: Vec<Placed>,
}

/// Lays `panels` out on as many sheets as they need, `gap` apart (`gap_from` says where the
/// gap comes from, for the message). Fails, naming the wall, when a panel does not fit on a
/// sheet either way round.
pub fn lay_out(panels: &[Panel], sheet: Sheet, gap: f64, gap_from: &str) -> Result<Layout> {
    let room = [sheet.width - 2.0 * gap, sheet.height - 2.0 * gap];
    // Size and lie of each panel: as it is, or turned where only that fits.
    let sized: Vec<(bool, Point, Point)> = panels
        .iter()
        .map(|p| {
            let (lo, hi) = p.bounds();
            let size = [hi[0] - lo[0], hi[1] - lo[1]];
            if size[0] <= room[0] && size[1] <= room[1] {
                Ok((false, lo, size))
            } else if size[1] <= room[0] && size[0] <= room[1] {
                let turned = p.outline.map(|q| [-q[1], q[0]]);
                let (lo, hi) = bounds(&turned);
                Ok((true, lo, [hi[0] - lo[0], hi[1] - lo[1]]))
            } else {
                Err(Error::option(
                    "sheet",
                    format!("{}x{}", rounded(sheet.width, 4), rounded(sheet.height, 4)),
                    format!(
                        "wall W{} is {} x {} and does not fit on a sheet with a \
                     gap of {} ({gap_from}) around it: give a larger sheet{}",
                        p.edge,
                        rounded(size[0], 4),
                        rounded(size[1], 4),
                        rounded(gap, 4),
                        if gap_from.contains("thickness") {
                            " or a thinner plate"
                        } else {
                            ""
                        }
                    ),
                ))
            }
        })
        .collect::<Result<_>>()?;
    let mut order: Vec<usize> = (0..panels.len()).collect();
    order.sort_by(|&i, &j| sized[j].2[1].total_cmp(&sized[i].2[1]).then(i.cmp(&j)));

    let mut placed: Vec<Option<Placed>> = vec![None; panels.len()];
    let (mut sheet_index, mut x, mut y, mut row_height) = (0, gap, gap, 0.0f64);
    for i in order {
        let (turned, origin, size) = sized[i];
        if x + size[0] > sheet.width - gap {
            // Next row.
            x = gap;
            y += row_height + gap;
            row_height = 0.0;
        }
        if y + size[1] > sheet.height - gap {
            sheet_index += 1;
            x = gap;
            y = gap;
            row_height = 0.0;
        }
        placed[i] = Some(Placed {
            panel: i,
            sheet: sheet_index,
            turned,
            offset: [x, y],
            origin,
        });
        x += size[0] + gap;
        row_height = row_height.max(size[1]);
    }
    Ok(Layout {
        sheet,
        gap,
        sheets: if panels.is_empty() {
            0
        } else {
            sheet_index + 1
        },
        placed: placed.into_iter().flatten().collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fabrication::unroll;
    use crate::generate::upright_hex_disk;

    /// Whether two convex outlines overlap (a separating axis among their sides' normals).
    fn overlap(a: &[Point], b: &[Point]) -> bool {
        let separated_by = |poly: &[Point]| {
            (0..poly.len()).any(|k| {
                let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
                let n = [q[1] - p[1], p[0] - q[0]];
                let proj = |s: &[Point]| {
                    let d: Vec<f64> = s.iter().map(|r| r[0] * n[0] + r[1] * n[1]).collect();
                    (
                        d.iter().copied().fold(f64::INFINITY, f64::min),
                        d.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                    )
                };
                let ((a0, a1), (b0, b1)) = (proj(a), proj(b));
                a1 <= b0 || b1 <= a0
            })
        };
        !(separated_by(a) || separated_by(b))
    }

    #[test]
    fn no_two_panels_overlap_and_each_keeps_the_gap_inside_its_sheet() {
        let (h, _) = upright_hex_disk(4.0, 0.3);
        let panels = unroll(&h, None);
        let sheet = Sheet {
            width: 4.0,
            height: 2.0,
        };
        let gap = 0.05;
        let layout = lay_out(&panels, sheet, gap, "test").unwrap();
        assert_eq!(layout.placed.len(), panels.len());
        assert!(layout.sheets >= 2, "{} sheets", layout.sheets);
        let outlines: Vec<(usize, Vec<Point>)> = layout
            .placed
            .iter()
            .map(|p| {
                (
                    p.sheet,
                    panels[p.panel]
                        .outline
                        .iter()
                        .map(|&q| p.place(q))
                        .collect(),
                )
            })
            .collect();
        for (sheet_index, outline) in &outlines {
            assert!(*sheet_index < layout.sheets);
            for q in outline {
                assert!(q[0] >= gap - 1e-12 && q[0] <= sheet.width - gap + 1e-12);
                assert!(q[1] >= gap - 1e-12 && q[1] <= sheet.height - gap + 1e-12);
            }
        }
        for i in 0..outlines.len() {
            for j in i + 1..outlines.len() {
                if outlines[i].0 == outlines[j].0 {
                    assert!(
                        !overlap(&outlines[i].1, &outlines[j].1),
                        "panels {i} and {j}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_panel_larger_than_the_sheet_is_refused_by_name() {
        let (h, _) = upright_hex_disk(2.0, 0.3);
        let panels = unroll(&h, None);
        let e = lay_out(
            &panels,
            Sheet {
                width: 0.5,
                height: 0.5,
            },
            0.01,
            "test",
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("sheet 0.5x0.5: wall W") && e.contains("does not fit"),
            "{e}"
        );
    }
}
