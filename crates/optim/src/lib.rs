//! argmin adapters (under construction).
