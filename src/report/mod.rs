//! Writing results: CSV and a magnitude plot.

pub mod chart;
pub mod csv;
pub mod plot;
