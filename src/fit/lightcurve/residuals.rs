//! The residuals: the request validated once, each evaluation's parameters put into its
//! scene, a light curve of the observed epochs simulated and compared with the magnitudes;
//! the evaluations counted against the fit's budget, and the best point kept.

use super::free::{assign, Target};
use super::observed::Observation;
use super::Run;
use crate::fit::solve::Residuals;
use crate::scene::request::{MaterialObject, MaterialSpec};
use crate::scene::{validate, Scene, ValidationError};
use glam::{DQuat, DVec3};
use std::cell::{Cell, RefCell};
use std::collections::BTreeMap;
use std::sync::atomic::Ordering;

/// The request as validated once, and what each evaluation changes.
pub(super) struct Problem<'a> {
    pub(super) scene: RefCell<Scene>,
    /// The observed epochs' body-frame vectors before any yaw: (sun, observer, earth).
    pub(super) base: Vec<(DVec3, DVec3, Option<DVec3>)>,
    /// Full material objects (presets expanded) of the materials a parameter touches.
    pub(super) materials: BTreeMap<usize, MaterialObject>,
    pub(super) targets: Vec<Target>,
    pub(super) observed: Vec<Observation>,
    /// Magnitude taken where the model has no light.
    pub(super) dark: f64,
    /// The engine, the cancellation and the evaluation count.
    pub(super) run: &'a Run<'a>,
    /// Most evaluations allowed now (counted by `run.evaluations`); an evaluation past it
    /// is refused and `spent` set.
    pub(super) budget: Cell<usize>,
    pub(super) spent: Cell<bool>,
    /// Set when the run was cancelled during an evaluation.
    pub(super) cancelled: Cell<bool>,
    /// The last evaluation's model magnitudes.
    pub(super) last: RefCell<Vec<Option<f64>>>,
    /// The evaluated point of lowest χ².
    pub(super) best: RefCell<Option<Best>>,
    /// A material error at some parameters (should not happen within the bounds).
    pub(super) error: RefCell<Option<ValidationError>>,
}

/// An evaluated point: its χ², parameters and residuals.
#[derive(Debug, Clone)]
pub(super) struct Best {
    pub(super) chi2: f64,
    pub(super) p: Vec<f64>,
    pub(super) residuals: Vec<f64>,
}

impl Problem<'_> {
    /// Light curves evaluated so far.
    pub(super) fn evaluations(&self) -> usize {
        self.run.evaluations.load(Ordering::Relaxed)
    }

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

    /// The model's magnitudes at `p`; `None` (and why kept in the problem) past the
    /// budget, on a cancellation, or when the parameters make no valid material.
    fn magnitudes(&self, p: &[f64]) -> Option<Vec<Option<f64>>> {
        if self.cancelled.get() || self.run.progress.is_cancelled() {
            self.cancelled.set(true);
            return None;
        }
        if self.evaluations() >= self.budget.get() {
            self.spent.set(true);
            return None;
        }
        if let Err(e) = self.apply(p) {
            *self.error.borrow_mut() = Some(e);
            return None;
        }
        self.run.evaluations.fetch_add(1, Ordering::Relaxed);
        match (self.run.engine)(&self.scene.borrow(), self.run.progress) {
            Ok(response) => Some(response.epochs.iter().map(|e| e.magnitude).collect()),
            Err(_) => {
                self.cancelled.set(true);
                None
            }
        }
    }

    /// Whether the fit must stop: cancelled, a material error, or the budget spent.
    pub(super) fn stopped(&self) -> bool {
        self.cancelled.get() || self.error.borrow().is_some() || self.spent.get()
    }
}

impl Residuals for Problem<'_> {
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
        let chi2: f64 = out.iter().map(|r| r * r).sum();
        let mut best = self.best.borrow_mut();
        if chi2.is_finite() && best.as_ref().is_none_or(|b| chi2 < b.chi2) {
            *best = Some(Best {
                chi2,
                p: p.to_vec(),
                residuals: out.to_vec(),
            });
        }
        true
    }
}
