//! Units and axes of exchanged files. The model is in model units with Z up; a file format
//! may require other units (glTF: metres) or another up axis (glTF: Y).

use crate::error::{Error, Result};
use crate::geometry::Vec3;
use serde::Serialize;

/// The length one model unit stands for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    Mm,
    Cm,
    #[default]
    M,
    In,
    Ft,
}

impl Units {
    pub const NAMES: &'static str = "mm, cm, m, in or ft";

    pub fn parse(text: &str) -> Result<Units> {
        Ok(match text.trim().to_ascii_lowercase().as_str() {
            "mm" => Units::Mm,
            "cm" => Units::Cm,
            "m" => Units::M,
            "in" => Units::In,
            "ft" => Units::Ft,
            _ => {
                return Err(Error::option(
                    "units",
                    text,
                    format!("expected {}", Units::NAMES),
                ))
            }
        })
    }

    /// One unit in metres.
    pub fn metres(self) -> f64 {
        match self {
            Units::Mm => 0.001,
            Units::Cm => 0.01,
            Units::M => 1.0,
            Units::In => 0.0254,
            Units::Ft => 0.3048,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Units::Mm => "mm",
            Units::Cm => "cm",
            Units::M => "m",
            Units::In => "in",
            Units::Ft => "ft",
        }
    }

    /// One millimetre in these units: the resolution at which wall lengths count as equal.
    pub fn millimetre(self) -> f64 {
        0.001 / self.metres()
    }
}

/// Which model axis points up in a written file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Up {
    /// As the model is: Z up (Rhino, most CAD).
    #[default]
    Z,
    /// Y up (glTF, three.js, Blender's OBJ default): (x, y, z) becomes (x, z, -y), a rotation,
    /// so nothing is mirrored.
    Y,
}

impl Up {
    pub fn parse(text: &str) -> Result<Up> {
        match text.trim().to_ascii_lowercase().as_str() {
            "z" => Ok(Up::Z),
            "y" => Ok(Up::Y),
            _ => Err(Error::option("up", text, "expected z or y")),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Up::Z => "z",
            Up::Y => "y",
        }
    }
}

/// Model coordinates to a file's: a scale (model units to the file's units) and an up axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub scale: f64,
    pub up: Up,
}

impl Frame {
    /// glTF's frame: metres, Y up.
    pub fn gltf(units: Units) -> Frame {
        Frame {
            scale: units.metres(),
            up: Up::Y,
        }
    }

    /// A point.
    pub fn point(&self, p: Vec3) -> [f64; 3] {
        let [x, y, z] = self.direction(p);
        [x * self.scale, y * self.scale, z * self.scale]
    }

    /// A direction (turned, not scaled).
    pub fn direction(&self, d: Vec3) -> [f64; 3] {
        match self.up {
            Up::Z => [d.x, d.y, d.z],
            Up::Y => [d.x, d.z, -d.y],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn y_up_is_a_rotation_that_takes_z_to_y() {
        let f = Frame {
            scale: 1.0,
            up: Up::Y,
        };
        assert_eq!(f.direction(Vec3::new(0.0, 0.0, 1.0)), [0.0, 1.0, 0.0]);
        // Right-handed stays right-handed: x cross y is still z.
        let [x, y, z] = [
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ]
        .map(|v| Vec3::from_slice(&f.direction(v)));
        assert!((x.cross(y) - z).norm() < 1e-15);
    }

    #[test]
    fn units_scale_to_metres_and_name_a_millimetre() {
        assert_eq!(Units::parse("MM").unwrap(), Units::Mm);
        assert!((Units::Ft.metres() - 0.3048).abs() < 1e-15);
        assert!((Units::Mm.millimetre() - 1.0).abs() < 1e-12);
        assert!((Units::M.millimetre() - 0.001).abs() < 1e-15);
        let e = Units::parse("furlong").unwrap_err().to_string();
        assert!(e.contains("units furlong"), "{e}");
    }
}
