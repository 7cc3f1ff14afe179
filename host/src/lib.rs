//! Arachis host library.
