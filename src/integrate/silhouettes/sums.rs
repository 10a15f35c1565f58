//! Patches summed whole: where a patch's faces share one material, its light is linear
//! over the cone of their normals ([`crate::brdf::Directions::linear_over`]) and no
//! direction's line crosses it, Σ_f A_f·f·cosθi·cosθr over its faces is lᵀ(Σ_f A_f n_f
//! n_fᵀ)v: one 3×3 form per patch instead of a BRDF and a visibility per face. This is
//! what keeps a finely tessellated smooth surface's cost with its patches and lines.

use super::direction::PatchState;
use super::patches::{Facing, Patches};
use super::{Scratch, Silhouettes};
use crate::geometry::{Cone, Faces};
use crate::integrate::per_direction::Toward;
use glam::{DMat3, DVec3};

/// A patch's material is not one.
const MIXED: u32 = u32::MAX;

/// Per patch, what summing it whole takes.
#[derive(Clone, Default)]
pub(super) struct PatchSums {
    /// Its faces' material, or [`MIXED`].
    material: Vec<u32>,
    /// The cone of its faces' normals (as stored in the faces).
    cone: Vec<Cone>,
    /// Σ A_f n_f n_fᵀ (m²): the same for either side, n nᵀ = (−n)(−n)ᵀ.
    form: Vec<DMat3>,
    /// Σ A_f (m²).
    area: Vec<f64>,
}

impl PatchSums {
    pub(super) fn build(faces: &Faces, patches: &Patches) -> PatchSums {
        let np = patches.len();
        let mut s = PatchSums {
            material: Vec::with_capacity(np),
            cone: Vec::with_capacity(np),
            form: Vec::with_capacity(np),
            area: Vec::with_capacity(np),
        };
        for p in 0..np {
            let of = patches.faces_of(p);
            let first = &faces.faces[of[0] as usize];
            let material = if of
                .iter()
                .all(|&f| faces.faces[f as usize].material == first.material)
            {
                first.material
            } else {
                MIXED
            };
            let cone = Cone::about(
                patches.axis[p],
                of.iter().map(|&f| faces.faces[f as usize].normal),
            );
            let (mut form, mut area) = (DMat3::ZERO, 0.0);
            for &f in of {
                let face = &faces.faces[f as usize];
                let n = face.normal;
                form += DMat3::from_cols(n * n.x, n * n.y, n * n.z) * face.area;
                area += face.area;
            }
            s.material.push(material);
            s.cone.push(cone);
            s.form.push(form);
            s.area.push(area);
        }
        s
    }
}

/// What one patch sends to the observer for a light linear over it, if all of it is
/// seen and lit.
pub struct PatchLight {
    /// Σ_f A_f n_f n_fᵀ, m².
    form: DMat3,
    /// Unit direction to the observer.
    v: DVec3,
}

impl PatchLight {
    /// Σ_f A_f (n_f·l)(n_f·v) = lᵀ(Σ_f A_f n_f n_fᵀ)v: m² times `l`'s units (W/sr for a
    /// light's vector L in W/(m²·sr), [`crate::brdf::Directions::linear_over`]).
    #[inline]
    pub fn of(&self, l: DVec3) -> f64 {
        l.dot(self.form * self.v)
    }
}

impl Silhouettes<'_> {
    /// How many patches there are.
    pub fn patches(&self) -> usize {
        self.patches.len()
    }

    /// Patch `p`'s faces.
    pub fn patch_faces(&self, p: usize) -> &[u32] {
        self.patches.faces_of(p)
    }

    /// Does no face of patch `p` show a side to unit `v`: one-sided faces (a patch is all
    /// one-sided or all two-sided) that face away from v as a whole (the patch's own
    /// cone, as every direction's step 1 asks it)? Such a patch sends the observer
    /// nothing, so its faces need not be read one by one.
    pub fn unseen(&self, p: usize, v: DVec3) -> bool {
        !self.polys.two_sided[self.patches.faces_of(p)[0] as usize]
            && self.patches.facing(p, v) == Facing::Away
    }

    /// Patch `p`'s material when all its faces share one, else `None`.
    #[inline]
    pub fn material(&self, p: usize) -> Option<u32> {
        let m = self.sums.material[p];
        (m != MIXED).then_some(m)
    }

    /// When all patch `p`'s faces share one material and are seen from one side from
    /// unit `v` (a one-sided patch facing v, or a two-sided one facing either way): its
    /// normals' cone on the side seen, its area (m²) and its form.
    pub fn summable(&self, p: usize, v: DVec3, two_sided: bool) -> Option<(Cone, f64, PatchLight)> {
        let s = &self.sums;
        if s.material[p] == MIXED {
            return None;
        }
        let cone = s.cone[p];
        let seen = if cone.min_dot(v) > 0.0 {
            cone
        } else if two_sided && cone.max_dot(v) < 0.0 {
            cone.flipped()
        } else {
            return None;
        };
        let light = PatchLight { form: s.form[p], v };
        Some((seen, s.area[p], light))
    }

    /// After [`Silhouettes::prepare`]: whether all of patch `p` is seen and sunlit, and
    /// seen and earthlit (`sun`, `earth`: the lights wanted of it), as
    /// [`Silhouettes::areas`] would find face by face; `None` when some direction decides
    /// its faces one by one.
    pub fn patch_visible(
        &self,
        scratch: &Scratch,
        p: usize,
        sun: bool,
        earth: bool,
    ) -> Option<(bool, bool)> {
        let clear = |k: Toward| -> Option<bool> {
            let dir = &scratch.dirs[k];
            if !dir.used {
                return Some(true);
            }
            match dir.patch[p] {
                PatchState::Clean => Some(dir.patch_count[p] == 0),
                _ => None,
            }
        };
        if !clear(Toward::View)? {
            return Some((false, false));
        }
        let sun = if sun { clear(Toward::Sun)? } else { false };
        let earth = if earth { clear(Toward::Earth)? } else { false };
        Some((sun, earth))
    }
}
