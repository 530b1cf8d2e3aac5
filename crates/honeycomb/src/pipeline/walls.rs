//! How the walls of a honeycomb stand on its design surface: the choice `--walls` makes.

use crate::geometry::Vec3;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::str::FromStr;

/// How the walls stand on S.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Walls {
    /// Node axes as close to S's normals as a honeycomb allows, cells of one size.
    #[default]
    Across,
    /// Every node axis along S's mean normal: the plan-view honeycomb.
    Uniform,
    /// Every node axis along this direction (unit).
    Direction(Vec3),
    /// Wherever the guided projection of the base mesh leaves them (the paper's algorithm,
    /// from walls orthogonal to S).
    Free,
}

impl Walls {
    /// `across`, `uniform`, `free` or `x,y,z`, as the option is written.
    pub fn label(&self) -> String {
        match self {
            Walls::Across => "across".into(),
            Walls::Uniform => "uniform".into(),
            Walls::Free => "free".into(),
            Walls::Direction(d) => crate::error::short_vector(*d),
        }
    }
}

impl FromStr for Walls {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Walls, String> {
        match s {
            "across" => return Ok(Walls::Across),
            "uniform" => return Ok(Walls::Uniform),
            "free" => return Ok(Walls::Free),
            _ => {}
        }
        crate::geometry::parse_direction(s)
            .map(Walls::Direction)
            .map_err(|e| format!("{e} (or across, uniform, free)"))
    }
}

/// `"across"`, `"uniform"`, `"free"`, or the direction as `[x, y, z]`.
impl Serialize for Walls {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            Walls::Direction(d) => d.to_array().serialize(s),
            other => s.serialize_str(&other.label()),
        }
    }
}

/// What [`Walls`] serializes to.
impl<'de> Deserialize<'de> for Walls {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Walls, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Written {
            Name(String),
            Direction([f64; 3]),
        }
        let text = match Written::deserialize(d)? {
            Written::Name(name) => name,
            Written::Direction([x, y, z]) => format!("{x},{y},{z}"),
        };
        text.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walls_parse_names_and_directions() {
        assert_eq!("across".parse::<Walls>(), Ok(Walls::Across));
        assert_eq!("uniform".parse::<Walls>(), Ok(Walls::Uniform));
        assert_eq!("free".parse::<Walls>(), Ok(Walls::Free));
        assert_eq!(
            "0,0,2".parse::<Walls>(),
            Ok(Walls::Direction(Vec3::new(0.0, 0.0, 1.0)))
        );
        let Ok(Walls::Direction(d)) = "1e-200,0,1e-200".parse::<Walls>() else {
            panic!("a tiny direction is still a direction");
        };
        assert!((d.norm() - 1.0).abs() < 1e-12 && (d.x - d.z).abs() < 1e-12);
        for bad in [
            "0,0,0", "1,2", "1,2,3,4", "x,1,2", "inf,0,1", "NaN,0,1", "sideways",
        ] {
            let e = bad.parse::<Walls>().unwrap_err();
            assert!(e.contains(bad), "{e}");
        }
        assert_eq!(
            serde_json::to_string(&Walls::Direction(Vec3::new(0.0, 0.0, 1.0))).unwrap(),
            "[0.0,0.0,1.0]"
        );
        assert_eq!(serde_json::to_string(&Walls::Across).unwrap(), "\"across\"");
        for walls in [
            Walls::Across,
            Walls::Free,
            Walls::Direction(Vec3::new(0.0, 1.0, 0.0)),
        ] {
            let text = serde_json::to_string(&walls).unwrap();
            assert_eq!(serde_json::from_str::<Walls>(&text).unwrap(), walls);
        }
        assert!(serde_json::from_str::<Walls>("[0, 0, 0]").is_err());
    }
}
