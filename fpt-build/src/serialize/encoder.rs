//! The vertex encoder of a file: the origin, half extent and shift a
//! model's bounds give, and each vertex and plane in the chosen format
//! (split out of `serialize.rs`).

use fpt_nostd::format::{VertexFormat, MAX_SHIFT, Q16_MAX};
use glam::DVec3;

use super::SerializeError;
use crate::geom::Plane;

/// How vertices are encoded, with the parameters derived from the model.
pub(super) struct Encoder {
    pub(super) format: VertexFormat,
    pub(super) origin: DVec3,
    pub(super) half_extent: [f32; 3],
    pub(super) shift: u8,
}

impl Encoder {
    pub(super) fn new(
        format: VertexFormat,
        lo: DVec3,
        hi: DVec3,
    ) -> Result<Encoder, SerializeError> {
        let origin = (lo + hi) * 0.5;
        let half = (hi - lo) * 0.5;
        // Rounded up so that every offset fits in [-half, half] after rounding.
        let half_extent = half.to_array().map(round_up_f32);
        if !half_extent.iter().all(|x| x.is_finite()) {
            return Err(SerializeError::OutOfRange("bounding box exceeds f32"));
        }
        let shift = if format == VertexFormat::Q32 {
            let m = (hi - origin).max(origin - lo).max_element();
            // The largest shift with round(m · 2^shift) < 2^31.
            (0..=MAX_SHIFT)
                .rev()
                .find(|&s| (m * 2f64.powi(i32::from(s))).round() <= f64::from(i32::MAX))
                .ok_or(SerializeError::OutOfRange("q32 needs |x - origin| < 2^31"))?
        } else {
            0
        };
        Ok(Encoder {
            format,
            origin,
            half_extent,
            shift,
        })
    }

    /// The stored bytes of vertex `v` (model coordinates).
    pub(super) fn encode(&self, v: DVec3) -> Result<Vec<u8>, SerializeError> {
        let rel = (v - self.origin).to_array();
        let mut out = Vec::with_capacity(self.format.vertex_len());
        match self.format {
            VertexFormat::F32 => {
                for x in rel {
                    // `+ 0.0` makes -0.0 into 0.0, so equal values share bytes.
                    let x = x as f32 + 0.0;
                    if !x.is_finite() {
                        return Err(SerializeError::NonFinite);
                    }
                    out.extend_from_slice(&x.to_le_bytes());
                }
            }
            VertexFormat::Q16 => {
                for (x, he) in rel.into_iter().zip(self.half_extent) {
                    let q = if he > 0.0 {
                        let m = f64::from(Q16_MAX);
                        (x / f64::from(he) * m).round().clamp(-m, m) as i16
                    } else {
                        0
                    };
                    out.extend_from_slice(&q.to_le_bytes());
                }
            }
            VertexFormat::Q32 => {
                let scale = 2f64.powi(i32::from(self.shift));
                for x in rel {
                    let q = (x * scale)
                        .round()
                        .clamp(-f64::from(i32::MAX), f64::from(i32::MAX))
                        as i32;
                    out.extend_from_slice(&q.to_le_bytes());
                }
            }
        }
        Ok(out)
    }

    /// The offset from the origin that `bytes` (from [`Self::encode`])
    /// decode to, in `f64`.
    pub(super) fn decode(&self, bytes: &[u8]) -> DVec3 {
        let mut c = [0f64; 3];
        match self.format {
            VertexFormat::F32 => {
                for (o, w) in c.iter_mut().zip(bytes.chunks_exact(4)) {
                    *o = f64::from(f32::from_le_bytes([w[0], w[1], w[2], w[3]]));
                }
            }
            VertexFormat::Q16 => {
                for ((o, w), he) in c
                    .iter_mut()
                    .zip(bytes.chunks_exact(2))
                    .zip(self.half_extent)
                {
                    let q = i16::from_le_bytes([w[0], w[1]]);
                    *o = f64::from(he) * f64::from(q) / f64::from(Q16_MAX);
                }
            }
            VertexFormat::Q32 => {
                let scale = 2f64.powi(-i32::from(self.shift));
                for (o, w) in c.iter_mut().zip(bytes.chunks_exact(4)) {
                    *o = f64::from(i32::from_le_bytes([w[0], w[1], w[2], w[3]])) * scale;
                }
            }
        }
        DVec3::from_array(c)
    }

    /// A plane re-expressed relative to the origin, in `f32`.
    pub(super) fn plane(&self, p: &Plane) -> Result<[f32; 4], SerializeError> {
        let d = p.d + p.normal.dot(self.origin);
        // `+ 0.0` makes -0.0 into 0.0, so that equal planes share bytes
        // (the sign of a zero changes no facing test).
        let out = [
            p.normal.x as f32 + 0.0,
            p.normal.y as f32 + 0.0,
            p.normal.z as f32 + 0.0,
            d as f32 + 0.0,
        ];
        if out.iter().all(|x| x.is_finite()) {
            Ok(out)
        } else {
            Err(SerializeError::NonFinite)
        }
    }
}

/// The smallest `f32` not below `x` (for `x ≥ 0`).
pub(super) fn round_up_f32(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) < x {
        f32::from_bits(y.to_bits() + 1)
    } else {
        y
    }
}
