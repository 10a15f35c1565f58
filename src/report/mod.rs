//! Writing results: CSV and a magnitude plot.

pub mod chart;
pub mod csv;
pub mod fit_plot;
pub mod plot;
