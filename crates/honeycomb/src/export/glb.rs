//! `structure.glb`: the honeycomb as one binary glTF 2.0 file, in metres with Y up, for
//! viewers and DCC tools. Its node names are a contract that other tools rely on:
//! `surface` (when S is known), `base`, `offset`, `walls` (children `W<edge>`), `node_axes`
//! and `cells` (children `C<face>`).
//!
//! Every wall and cell is a mesh of its own vertices, so that an importer that copies a whole
//! accessor per mesh stays linear; the walls' and cells' accessors share buffer views, and
//! walls of one colour, or cells of one corner count, share a colour or index accessor.

use super::{Frame, Model};
use crate::error::{Error, Result};
use crate::render::color;
use gltf_json as json;
use json::accessor::{ComponentType, GenericComponentType, Type};
use json::buffer::{Stride, Target};
use json::material::{AlphaMode, PbrBaseColorFactor, PbrMetallicRoughness, StrengthFactor};
use json::mesh::{Mode, Semantic};
use json::validation::{Checked::Valid, USize64};
use json::{Accessor, Index, Material, Mesh, Node, Root};
use std::collections::{BTreeMap, HashMap};

/// Walls leaning this far (degrees) or more get the colour map's top colour.
const LEAN_FULL_SCALE_DEG: f64 = 45.0;

/// The binary glTF of `model`.
pub fn glb_bytes(model: &Model) -> Result<Vec<u8>> {
    let frame = Frame::gltf(model.units);
    let h = &model.honeycomb;
    let mut g = Builder::new();

    let plain = |rgba: [f32; 4]| Material {
        alpha_mode: Valid(if rgba[3] < 1.0 {
            AlphaMode::Blend
        } else {
            AlphaMode::Opaque
        }),
        // Either side of a sheet may face the viewer.
        double_sided: true,
        pbr_metallic_roughness: PbrMetallicRoughness {
            base_color_factor: PbrBaseColorFactor(rgba),
            metallic_factor: StrengthFactor(0.0),
            roughness_factor: StrengthFactor(0.8),
            ..Default::default()
        },
        ..Default::default()
    };
    let named = |name: &str, m: Material| Material {
        name: Some(name.into()),
        ..m
    };
    let mut scene_nodes = Vec::new();

    if let Some(s) = &model.surface_mesh {
        let material = g.root.push(named("surface", plain([0.5, 0.5, 0.5, 0.35])));
        let positions = g.positions(s.vertices.iter().map(|&p| frame.point(p)))?;
        let indices = g.indices(&fan(&s.faces));
        let mesh = g.mesh(
            "surface",
            positions,
            None,
            indices,
            material,
            Mode::Triangles,
        );
        scene_nodes.push(g.node("surface", Some(mesh), None, None));
    }

    // M and M' side by side in the positions, so that the node axes can index both.
    let nv = h.base.vertices.len();
    let base_material = g.root.push(named("base", plain([0.06, 0.06, 0.07, 1.0])));
    let offset_material = g.root.push(named("offset", plain([0.62, 0.64, 0.68, 1.0])));
    let (base, offset, both) = g.two_blocks(
        h.base.vertices.iter().map(|&p| frame.point(p)),
        h.offset.vertices.iter().map(|&p| frame.point(p)),
    )?;
    let faces = g.indices(&fan(&h.base.faces));
    let mesh = g.mesh("base", base, None, faces, base_material, Mode::Triangles);
    scene_nodes.push(g.node("base", Some(mesh), None, None));
    let mesh = g.mesh(
        "offset",
        offset,
        None,
        faces,
        offset_material,
        Mode::Triangles,
    );
    scene_nodes.push(g.node("offset", Some(mesh), None, None));

    let wall_material = g.root.push(named("walls", plain([1.0, 1.0, 1.0, 1.0])));
    let lean = model.wall_lean_deg();
    let quad = g.indices(&[0, 1, 2, 0, 2, 3]);
    let mut colours: HashMap<(u8, u8, u8), Index<Accessor>> = HashMap::new();
    let mut walls = Vec::with_capacity(h.edges.len());
    for (e, &[a, b]) in h.edges.iter().enumerate() {
        let name = format!("W{e}");
        let positions = g.positions(h.wall(e).into_iter().map(|p| frame.point(p)))?;
        let rgb = color((lean[e] / LEAN_FULL_SCALE_DEG).clamp(0.0, 1.0));
        let colour = *colours.entry(rgb).or_insert_with(|| g.colour(rgb));
        let mesh = g.mesh(
            &name,
            positions,
            Some(colour),
            quad,
            wall_material,
            Mode::Triangles,
        );
        let extras = serde_json::json!({
            "edge": e,
            "nodes": [a, b],
            "lean_deg": lean[e],
        });
        walls.push(g.node(&name, Some(mesh), None, Some(extras)));
    }
    scene_nodes.push(g.node("walls", None, Some(walls), None));

    let axes_material = g
        .root
        .push(named("node_axes", plain([0.95, 0.3, 0.05, 1.0])));
    let ends: Vec<u32> = (0..nv as u32).flat_map(|i| [i, nv as u32 + i]).collect();
    let ends = g.indices(&ends);
    let mesh = g.mesh("node_axes", both, None, ends, axes_material, Mode::Lines);
    scene_nodes.push(g.node("node_axes", Some(mesh), None, None));

    let mut fans: HashMap<usize, Index<Accessor>> = HashMap::new();
    let mut cells = Vec::with_capacity(h.base.faces.len());
    for (f, face) in h.base.faces.iter().enumerate() {
        let name = format!("C{f}");
        let positions = g.positions(face.iter().map(|&v| frame.point(h.base.vertices[v])))?;
        let indices = *fans
            .entry(face.len())
            .or_insert_with(|| g.indices(&fan(&[(0..face.len()).collect()])));
        let mesh = g.mesh(
            &name,
            positions,
            None,
            indices,
            base_material,
            Mode::Triangles,
        );
        let extras = serde_json::json!({ "face": f, "nodes": face });
        cells.push(g.node(&name, Some(mesh), None, Some(extras)));
    }
    scene_nodes.push(g.node("cells", None, Some(cells), None));

    let scene = g.root.push(json::Scene {
        extensions: None,
        extras: None,
        name: Some("honeycomb".into()),
        nodes: scene_nodes,
    });
    g.root.scene = Some(scene);
    g.root.asset.generator = Some(format!("honeycomb {}", env!("CARGO_PKG_VERSION")));
    g.root.asset.extras = raw(serde_json::json!({
        "units": "m",
        "source_units": model.units.name(),
    }));
    g.finish()
}

/// The faces fan-triangulated from their first corner; a triangle that repeats a vertex is
/// left out (it would draw nothing).
fn fan(faces: &[Vec<usize>]) -> Vec<u32> {
    let mut out = Vec::with_capacity(faces.iter().map(|f| 3 * f.len()).sum());
    for face in faces {
        for k in 1..face.len().saturating_sub(1) {
            let [a, b, c] = [face[0], face[k], face[k + 1]];
            if a != b && b != c && c != a {
                out.extend([a, b, c].map(|v| v as u32));
            }
        }
    }
    out
}

fn raw(value: serde_json::Value) -> json::Extras {
    // A Value always serializes.
    Some(serde_json::value::to_raw_value(&value).expect("JSON value"))
}

/// The JSON root and the binary data behind it, in three blocks that become one buffer
/// view each: positions, colours (both float VEC3) and indices (u32).
struct Builder {
    root: Root,
    positions: Vec<[f32; 3]>,
    colours: Vec<[f32; 3]>,
    indices: Vec<u32>,
    /// Accessors per block, whose view (and byte offset) is known only at the end.
    position_accessors: Vec<Index<Accessor>>,
    colour_accessors: Vec<Index<Accessor>>,
    index_accessors: Vec<Index<Accessor>>,
}

impl Builder {
    fn new() -> Builder {
        Builder {
            root: Root::default(),
            positions: Vec::new(),
            colours: Vec::new(),
            indices: Vec::new(),
            position_accessors: Vec::new(),
            colour_accessors: Vec::new(),
            index_accessors: Vec::new(),
        }
    }

    /// Points appended to the positions, with their bounds (which glTF requires).
    fn positions(&mut self, points: impl Iterator<Item = [f64; 3]>) -> Result<Index<Accessor>> {
        let first = self.positions.len();
        for p in points {
            let p = p.map(|x| x as f32);
            if !p.iter().all(|x| x.is_finite()) {
                return Err(Error::Mesh(
                    "glb: a vertex is not finite as a single-precision float in metres".into(),
                ));
            }
            self.positions.push(p);
        }
        Ok(self.position_range(first, self.positions.len()))
    }

    fn position_range(&mut self, first: usize, end: usize) -> Index<Accessor> {
        let bounds = bounds(&self.positions[first..end]);
        let accessor = accessor(first, end - first, Type::Vec3, bounds);
        let index = self.root.push(accessor);
        self.position_accessors.push(index);
        index
    }

    /// Two point sets one after the other: an accessor for each and one for both.
    fn two_blocks(
        &mut self,
        first: impl Iterator<Item = [f64; 3]>,
        second: impl Iterator<Item = [f64; 3]>,
    ) -> Result<(Index<Accessor>, Index<Accessor>, Index<Accessor>)> {
        let start = self.positions.len();
        let a = self.positions(first)?;
        let b = self.positions(second)?;
        Ok((a, b, self.position_range(start, self.positions.len())))
    }

    /// Four vertices of one sRGB colour, for a wall, in glTF's linear COLOR_0.
    fn colour(&mut self, (r, g, b): (u8, u8, u8)) -> Index<Accessor> {
        let first = self.colours.len();
        let rgb = [r, g, b].map(linear);
        self.colours.extend([rgb; 4]);
        let accessor = accessor(first, 4, Type::Vec3, None);
        let index = self.root.push(accessor);
        self.colour_accessors.push(index);
        index
    }

    fn indices(&mut self, indices: &[u32]) -> Index<Accessor> {
        let first = self.indices.len();
        self.indices.extend_from_slice(indices);
        let accessor = accessor(first, indices.len(), Type::Scalar, None);
        let index = self.root.push(accessor);
        self.index_accessors.push(index);
        index
    }

    fn mesh(
        &mut self,
        name: &str,
        positions: Index<Accessor>,
        colours: Option<Index<Accessor>>,
        indices: Index<Accessor>,
        material: Index<Material>,
        mode: Mode,
    ) -> Index<Mesh> {
        let mut attributes = BTreeMap::from([(Valid(Semantic::Positions), positions)]);
        if let Some(c) = colours {
            attributes.insert(Valid(Semantic::Colors(0)), c);
        }
        self.root.push(Mesh {
            extensions: None,
            extras: None,
            name: Some(name.into()),
            primitives: vec![json::mesh::Primitive {
                attributes,
                extensions: None,
                extras: None,
                indices: Some(indices),
                material: Some(material),
                mode: Valid(mode),
                targets: None,
            }],
            weights: None,
        })
    }

    fn node(
        &mut self,
        name: &str,
        mesh: Option<Index<Mesh>>,
        children: Option<Vec<Index<Node>>>,
        extras: Option<serde_json::Value>,
    ) -> Index<Node> {
        self.root.push(Node {
            name: Some(name.into()),
            mesh,
            // An empty list is not valid glTF.
            children: children.filter(|c| !c.is_empty()),
            extras: extras.and_then(raw),
            ..Default::default()
        })
    }

    /// The buffer views over the three blocks, and the GLB container.
    fn finish(mut self) -> Result<Vec<u8>> {
        let mut bin: Vec<u8> = Vec::with_capacity(
            12 * (self.positions.len() + self.colours.len()) + 4 * self.indices.len(),
        );
        let buffer = self.root.push(json::Buffer {
            // Set below.
            byte_length: USize64(0),
            name: None,
            uri: None,
            extensions: None,
            extras: None,
        });
        let blocks = [
            (
                "positions",
                self.positions
                    .iter()
                    .flatten()
                    .flat_map(|x| x.to_le_bytes())
                    .collect(),
                &self.position_accessors,
                Target::ArrayBuffer,
            ),
            (
                "colours",
                self.colours
                    .iter()
                    .flatten()
                    .flat_map(|x| x.to_le_bytes())
                    .collect(),
                &self.colour_accessors,
                Target::ArrayBuffer,
            ),
            (
                "indices",
                self.indices
                    .iter()
                    .flat_map(|x| x.to_le_bytes())
                    .collect::<Vec<u8>>(),
                &self.index_accessors,
                Target::ElementArrayBuffer,
            ),
        ];
        for (name, bytes, accessors, target) in blocks {
            if accessors.is_empty() {
                continue;
            }
            let view = self.root.push(json::buffer::View {
                buffer,
                byte_length: USize64::from(bytes.len()),
                byte_offset: Some(USize64::from(bin.len())),
                // Vertex attributes of several accessors in one view need a stride; indices
                // must have none.
                byte_stride: (target == Target::ArrayBuffer).then_some(Stride(12)),
                name: Some(name.into()),
                target: Some(Valid(target)),
                extensions: None,
                extras: None,
            });
            for &a in accessors {
                self.root.accessors[a.value()].buffer_view = Some(view);
            }
            bin.extend_from_slice(&bytes);
        }
        self.root.buffers[buffer.value()].byte_length = USize64::from(bin.len());
        let json = json::serialize::to_vec(&self.root)
            .map_err(|e| Error::Mesh(format!("glb: the glTF JSON does not serialize: {e}")))?;
        container(json, bin)
    }
}

/// An accessor of `count` elements from element `first` of its block.
fn accessor(first: usize, count: usize, type_: Type, bounds: Bounds) -> Accessor {
    let component = match type_ {
        Type::Scalar => ComponentType::U32,
        _ => ComponentType::F32,
    };
    Accessor {
        // Set in `finish`.
        buffer_view: None,
        byte_offset: Some(USize64::from(4 * type_.multiplicity() * first)),
        count: USize64::from(count),
        component_type: Valid(GenericComponentType(component)),
        extensions: None,
        extras: None,
        type_: Valid(type_),
        min: bounds.map(|(lo, _)| serde_json::json!(lo)),
        max: bounds.map(|(_, hi)| serde_json::json!(hi)),
        name: None,
        normalized: false,
        sparse: None,
    }
}

/// Component-wise minimum and maximum of a non-empty list.
fn bounds(points: &[[f32; 3]]) -> Bounds {
    let first = *points.first()?;
    Some(points.iter().fold((first, first), |(lo, hi), p| {
        (
            [0, 1, 2].map(|i| lo[i].min(p[i])),
            [0, 1, 2].map(|i| hi[i].max(p[i])),
        )
    }))
}

type Bounds = Option<([f32; 3], [f32; 3])>;

/// An sRGB byte as a linear intensity.
fn linear(c: u8) -> f32 {
    let c = c as f64 / 255.0;
    let l = if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    };
    l as f32
}

/// The GLB container: a 12-byte header, the JSON chunk padded with spaces and the BIN chunk
/// padded with zeros, each to a multiple of four bytes.
fn container(mut json: Vec<u8>, mut bin: Vec<u8>) -> Result<Vec<u8>> {
    json.resize(json.len().next_multiple_of(4), b' ');
    bin.resize(bin.len().next_multiple_of(4), 0);
    let total = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    let total = u32::try_from(total)
        .map_err(|_| Error::Mesh(format!("glb: {total} bytes, more than a GLB holds")))?;
    let mut out = Vec::with_capacity(total as usize);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total.to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    if !bin.is_empty() {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fan_leaves_out_triangles_that_repeat_a_vertex() {
        assert_eq!(fan(&[vec![0, 1, 2, 3]]), [0, 1, 2, 0, 2, 3]);
        assert_eq!(fan(&[vec![4, 5, 5, 6]]), [4, 5, 6]);
    }

    #[test]
    fn srgb_bytes_become_linear_intensities() {
        assert_eq!(linear(0), 0.0);
        assert_eq!(linear(255), 1.0);
        // sRGB mid-grey is about a fifth of full intensity.
        assert!((linear(128) - 0.2158).abs() < 1e-3);
    }

    #[test]
    fn the_container_pads_its_chunks_to_four_bytes() {
        let glb = container(b"{}".to_vec(), vec![1, 2, 3, 4, 5]).unwrap();
        assert_eq!(&glb[..4], b"glTF");
        assert_eq!(
            u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize,
            glb.len()
        );
        assert_eq!(&glb[12..24], b"\x04\0\0\0JSON{}  ");
        assert_eq!(&glb[24..32], b"\x08\0\0\0BIN\0");
        assert_eq!(&glb[32..], [1, 2, 3, 4, 5, 0, 0, 0]);
    }
}
