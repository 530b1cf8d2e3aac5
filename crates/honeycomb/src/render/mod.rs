//! Pictures of honeycombs for people: colour-coded walls (paper Fig. 8) with a colour bar, the
//! quads that cap them, a shading device's cells by the light they let through, and the
//! spherical image (Figs. 4-5).

mod colormap;
mod legend;
mod measure;
mod quads;
mod scene;
mod shading;
mod spherical;
mod view;
mod walls;

pub use colormap::color;
pub use legend::Ramp;
pub use measure::WallMeasure;
pub use quads::quads_scene;
pub use scene::{escape, Scene, Shape, TextStyle};
pub use shading::{shading_scene, DesignLight};
pub use spherical::spherical_scene;
pub use view::{Camera, View};
pub use walls::{polygons_scene, walls_scene, Coloring};

/// The narrowest picture whose drawing, colour bar and legend all fit, and the widest one drawn: a PNG is held in
/// memory about four times over at 3 bytes a pixel (0.8 GB at 8000 pixels square).
pub const WIDTHS: std::ops::RangeInclusive<u32> = 480..=8000;

/// Refuses a picture width outside [`WIDTHS`], before anything is drawn.
pub fn check_width(width: u32) -> crate::Result<()> {
    if !WIDTHS.contains(&width) {
        return Err(crate::Error::option(
            "width",
            width,
            format!("expected {} to {} pixels", WIDTHS.start(), WIDTHS.end()),
        ));
    }
    Ok(())
}
