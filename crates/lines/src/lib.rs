//! Fairing a whole lines plan: a ship's table of offsets (stations, waterlines, buttocks and
//! edge lines) faired as one hull.
//!
//! A lines plan describes one hull by three families of plane cuts — stations y(z) at fixed x,
//! waterlines y(x) at fixed z, buttocks z(x) at fixed y — and edge lines (sheer, chine, rabbet);
//! a table of offsets lists their crossings, rounded to the drawing's precision. Faired one line
//! at a time, the views disagree again at every crossing. Here one fair surface is fitted to
//! every offset at once (a tensor-product cubic B-spline, half-breadth as a function of x and
//! height, with a penalty on the jumps of its third derivatives along both directions and a
//! robust weight per offset), and every offset is cut back from it: the views agree at every
//! crossing to round-off, offsets move by about the rounding, and an offset that cannot be made
//! to agree is flagged with the value the hull suggests instead of bending the hull.
//!
//! The front ends are thin: [`read_table`], [`fair`], then the writers of [`mod@write`].

pub mod error;
pub mod table;

pub use error::{Error, Result};
pub use table::{read_table, Cell, Coord, Kind, Layout, Line, Table};
mod features;
pub mod generate;
mod hull;
mod knuckle;
pub mod lofting;
pub mod report;
pub mod write;

mod fit;
mod spline;

pub use lofting::{fair, Faired, Hull, Settings, Source};
pub use report::{HullFit, LineReport, OffsetReport, Report, Stats};
