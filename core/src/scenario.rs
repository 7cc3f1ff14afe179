//! Deterministic set-ups of the standard scenarios (bench bed, pours).
