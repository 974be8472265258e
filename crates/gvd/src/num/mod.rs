//! Certified numerics: intervals, Bernstein forms, sparse polynomials, root isolation.

pub mod bernstein;
pub mod interval;
pub mod poly;
pub mod roots;

pub use interval::Interval;
