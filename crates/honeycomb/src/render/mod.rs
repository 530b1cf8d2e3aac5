//! Pictures of honeycombs for people: colour-coded walls (paper Fig. 8) with a colour bar, and
//! the spherical image (Figs. 4-5).

mod colormap;
mod spherical;
mod svg;
mod view;

pub use colormap::{color, Scale};
pub use spherical::svg_spherical;
pub use svg::{svg, Coloring};
pub use view::View;
