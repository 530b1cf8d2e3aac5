//! Pictures of honeycombs for people: colour-coded walls (paper Fig. 8) with a colour bar.

mod colormap;
mod svg;
mod view;

pub use colormap::{color, Scale};
pub use svg::{svg, Coloring};
pub use view::View;
