//! Writing results: CSV and a magnitude plot.

pub mod csv;
pub mod plot;
