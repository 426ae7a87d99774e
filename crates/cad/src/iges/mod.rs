//! IGES 5.3: entity 126 (rational B-spline curve) and 128 (rational B-spline surface).
//!
//! A file is fixed-form ASCII, 80 columns: Start (`S`), Global (`G`), Directory Entry (`D`,
//! two lines per entity), Parameter Data (`P`) and Terminate (`T`) sections, the section
//! letter in column 73 and a sequence number in columns 74–80.
//!
//! - [`write()`]: each curve as one entity 126 (PROP1 planar for a 2D curve with the normal
//!   (0, 0, 1), PROP2 closed, PROP3 polynomial when all weights are equal), each surface as one
//!   entity 128; the Global section carries the unit (parameters 14–15), the model's
//!   resolution (19) and the largest coordinate (20). Reals are written with the shortest
//!   digits that read back bit for bit ([`crate::number::real`]), so a round trip through
//!   [`read`] returns the same knots, weights and control points to the last bit.
//! - [`read`]: every entity 126 and 128 (with its transformation matrix, entity 124, applied
//!   to the control points), except curves flagged as parameter-space curves (entity use
//!   flag 05, the 2D curves of a curve on a surface). Other entities are skipped. Errors name
//!   the line.

mod read;
mod write;

pub use read::read;
pub use write::write;
