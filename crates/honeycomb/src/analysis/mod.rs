//! Analysis of a realized honeycomb beyond the Figure 16 measures: its spherical image.

mod spherical_area;
mod spherical_image;

pub use spherical_area::{oriented_area, total_turning, triangle_area};
pub use spherical_image::{spherical_image, CellImage, SphericalImage};
