//! fairness (under construction).
