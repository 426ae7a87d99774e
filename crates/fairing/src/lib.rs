//! fairing (under construction).
