//! The fairing framework, re-exported in one place.
//!
//! See the README for the architecture: representations ([`curve_repr`]) ← indicators and
//! criteria ([`fairness`]) ← optimisation adapters ([`optim`]) ← strategies and pipelines
//! ([`fairing`]) ← the door every front end goes through ([`fair_door`]: fair a curve, fair a
//! surface, measure) ← the `fair` command ([`fair_cli`]); faired shapes into CAD files ([`cad`]).

pub use cad;
pub use curve_repr;
pub use fair_cli;
pub use fair_door;
pub use fairing;
pub use fairness;
pub use optim;
