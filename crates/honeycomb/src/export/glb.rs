//! Placeholder until the glTF writer lands.
use super::Model;
pub fn glb_bytes(_model: &Model) -> crate::Result<Vec<u8>> {
    Err(crate::Error::Parameter("glb: not yet".into()))
}
