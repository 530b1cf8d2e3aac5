//! Analysis of a realized honeycomb beyond the Figure 16 measures: its spherical image, and
//! the share of light it lets through as a shading device.

mod light;
mod shading;
mod spherical_area;
mod spherical_image;

pub use light::{light_share, read_directions, sun_light, LightShare, DEFAULT_LIGHT_SAMPLES};
pub use shading::{
    extruded_along_normals, shading_against_normals, shading_report, LightComparison,
    ShadingReport, Shares, SHADING_DEPTH, SHADING_GOAL,
};
pub use spherical_image::{spherical_image, CellImage, SphericalImage};
