//! Pictures of honeycombs for people: colour-coded walls (paper Fig. 8) with a colour bar, and
//! the spherical image (Figs. 4-5).

mod colormap;
mod png;
mod scene;
mod spherical;
mod svg;
mod view;

pub use colormap::{color, Scale};
pub use scene::{Scene, Shape};
pub use spherical::spherical_scene;
pub use svg::{walls_scene, Coloring};
pub use view::View;
