//! The residuals: the request validated once, each evaluation's parameters put into its
//! scene, a light curve of the observed epochs simulated and compared with the magnitudes.

use super::free::{assign, Target};
use super::observed::Observation;
use crate::fit::solve::Residuals;
use crate::integrate::simulate;
use crate::scene::request::{MaterialObject, MaterialSpec};
use crate::scene::{validate, Scene, ValidationError};
use glam::{DQuat, DVec3};
use std::cell::{Cell, RefCell};
use std::collections::BTreeMap;

/// The request as validated once, and what each evaluation changes.
pub(super) struct Problem {
    pub(super) scene: RefCell<Scene>,
    /// The observed epochs' body-frame vectors before any yaw: (sun, observer, earth).
    pub(super) base: Vec<(DVec3, DVec3, Option<DVec3>)>,
    /// Full material objects (presets expanded) of the materials a parameter touches.
    pub(super) materials: BTreeMap<usize, MaterialObject>,
    pub(super) targets: Vec<Target>,
    pub(super) observed: Vec<Observation>,
    /// Magnitude taken where the model has no light.
    pub(super) dark: f64,
    /// The last evaluation's model magnitudes.
    pub(super) last: RefCell<Vec<Option<f64>>>,
    pub(super) evaluations: Cell<usize>,
    /// A material error at some parameters (should not happen within the bounds).
    pub(super) error: RefCell<Option<ValidationError>>,
}

impl Problem {
    /// Puts parameters `p` into the scene.
    fn apply(&self, p: &[f64]) -> Result<(), ValidationError> {
        let mut scene = self.scene.borrow_mut();
        let (materials, yaw) = assign(&self.targets, &self.materials, p);
        let yaw = yaw.unwrap_or(0.0);
        for (index, m) in materials {
            scene.materials[index] = validate::material(
                &format!("object.materials[{index}]"),
                &MaterialSpec::Full(m),
            )?;
        }
        let turn = DQuat::from_rotation_z(-yaw.to_radians());
        for (e, (sun, obs, earth)) in scene.epochs.iter_mut().zip(&self.base) {
            e.sun = turn * *sun;
            e.observer = turn * *obs;
            e.earth = earth.map(|v| turn * v);
        }
        Ok(())
    }

    fn magnitudes(&self, p: &[f64]) -> Option<Vec<Option<f64>>> {
        if let Err(e) = self.apply(p) {
            *self.error.borrow_mut() = Some(e);
            return None;
        }
        self.evaluations.set(self.evaluations.get() + 1);
        let response = simulate(&self.scene.borrow());
        Some(response.epochs.iter().map(|e| e.magnitude).collect())
    }
}

impl Residuals for Problem {
    fn count(&self) -> usize {
        self.observed.len()
    }

    fn eval(&self, p: &[f64], out: &mut [f64]) -> bool {
        let Some(mags) = self.magnitudes(p) else {
            return false;
        };
        for ((o, obs), m) in out.iter_mut().zip(&self.observed).zip(&mags) {
            *o = (obs.magnitude - m.unwrap_or(self.dark)) / obs.sigma;
        }
        *self.last.borrow_mut() = mags;
        true
    }
}
