//! The optional corner normal section (see [`crate::format`]): one vertex
//! normal per polygon corner, which the `smooth` effect lights.

use super::Tree;
use crate::format::{rec, FormatError, NORMAL_LEN};

impl<'a> Tree<'a> {
    /// Whether the file has the corner normal section (the `smooth`
    /// effect was declared when it was built).
    ///
    /// ```
    /// # let bytes: &[u8] = include_bytes!("../../../firmware/trees/vise.fpt");
    /// let tree = fpt_nostd::reader::Tree::from_bytes(bytes).unwrap();
    /// assert!(!tree.has_normals()); // built without `smooth`
    /// assert_eq!(tree.corner_normal(0, 0), None);
    /// ```
    pub fn has_normals(&self) -> bool {
        !self.normals.is_empty()
    }

    /// The vertex normal of corner `i` of polygon `id` (its vertex `i`):
    /// the unit normal times 127, on the polygon's front side. `None`
    /// without the section, for an id out of range or past the polygon's
    /// last corner.
    #[inline]
    pub fn corner_normal(&self, id: u32, i: usize) -> Option<[i8; 3]> {
        if self.normals.is_empty() || id >= self.counts.polygons {
            return None;
        }
        let (first, end) = self.g.polygon_range(id);
        let j = (first as usize).checked_add(i)?;
        if j >= end as usize {
            return None;
        }
        Some(normal_at(self.normals, j))
    }

    /// Every corner normal is non-zero with components in `−127..=127`.
    pub(super) fn check_normals(&self) -> Result<(), FormatError> {
        for j in 0..self.counts.normals {
            let n = normal_at(self.normals, j as usize);
            if n == [0; 3] || n.contains(&i8::MIN) {
                return Err(FormatError::BadNormal(j));
            }
        }
        Ok(())
    }
}

/// Record `j` of a normal section (zeros past its end).
#[inline(always)]
fn normal_at(section: &[u8], j: usize) -> [i8; 3] {
    rec::<NORMAL_LEN>(section, j).map(|b| b as i8)
}
