//! A stream of 64-bit state words in either direction ([`StateWords`]): the layer under
//! checkpoints ([`crate::world::checkpoint`]), kept apart from the world so that the step's
//! own parts (the neighbour list) can write and read their state through it.
//!
//! ```
//! use arachis_core::state_words::{StateWords, WordReader, WordWriter};
//! let mut out = Vec::new();
//! let mut x = 7u64;
//! WordWriter::new(|w| out.push(w)).word(&mut x).unwrap();
//! let mut y = 0u64;
//! WordReader::new(out.into_iter()).word(&mut y).unwrap();
//! assert_eq!(y, 7);
//! ```

use core::fmt;

use crate::num::{Quat, Scalar, Vec3};

/// First word of every checkpoint ("ARACHCKP" in ASCII).
pub const MAGIC: u64 = u64::from_be_bytes(*b"ARACHCKP");
/// Layout version; a reader refuses any other.
pub const VERSION: u64 = 1;

/// Why a checkpoint could not be read (or, for [`CheckpointError::Refused`], written).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CheckpointError {
    /// The world was set up differently from the one that wrote the checkpoint.
    Mismatch {
        /// What differs.
        what: &'static str,
        /// The world's value.
        world: u64,
        /// The checkpoint's value.
        checkpoint: u64,
    },
    /// A value no world could hold.
    Corrupt {
        /// Which value.
        what: &'static str,
        /// The value read.
        value: u64,
    },
    /// The stream ended early.
    Truncated,
    /// The sink refused a word (a full buffer or a failed write).
    Refused,
    /// A world with slow bodies was asked for a checkpoint within a multi-rate cycle, whose
    /// sums the words do not hold ([`crate::step::multirate`]); write one when the step count
    /// is a multiple of the stride.
    MidCycle {
        /// Steps done.
        steps: u64,
        /// Steps per cycle.
        stride: u32,
    },
}

impl fmt::Display for CheckpointError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            CheckpointError::Mismatch {
                what,
                world,
                checkpoint,
            } => write!(
                f,
                "the checkpoint was written by a world set up differently: {what} is {checkpoint} \
                 there and {world} here"
            ),
            CheckpointError::Corrupt { what, value } => {
                write!(
                    f,
                    "the checkpoint is damaged: {what} = {value} is impossible"
                )
            }
            CheckpointError::Truncated => write!(f, "the checkpoint ends early"),
            CheckpointError::Refused => write!(f, "the checkpoint's words could not be written"),
            CheckpointError::MidCycle { steps, stride } => write!(
                f,
                "no checkpoint within a multi-rate cycle: {steps} steps done, not a multiple of                  the slow stride {stride}"
            ),
        }
    }
}

/// A stream of state words, in either direction.
pub trait StateWords {
    /// A changing word: a writer records `*w`, a reader replaces it with the next word.
    fn word(&mut self, w: &mut u64) -> Result<(), CheckpointError>;
    /// A word set-up fixes (a count, a kind, a material): a writer records it, a reader
    /// checks that the next word equals it.
    fn same(&mut self, w: u64, what: &'static str) -> Result<(), CheckpointError>;
}

/// Writes every word to a sink (a `Vec::push`, a file's buffered writer).
pub struct WordWriter<F: FnMut(u64)> {
    sink: F,
}

impl<F: FnMut(u64)> WordWriter<F> {
    /// A writer into `sink`.
    pub fn new(sink: F) -> Self {
        WordWriter { sink }
    }
}

impl<F: FnMut(u64)> StateWords for WordWriter<F> {
    fn word(&mut self, w: &mut u64) -> Result<(), CheckpointError> {
        (self.sink)(*w);
        Ok(())
    }
    fn same(&mut self, w: u64, _: &'static str) -> Result<(), CheckpointError> {
        (self.sink)(w);
        Ok(())
    }
}

/// Reads words from an iterator.
pub struct WordReader<I: Iterator<Item = u64>> {
    words: I,
}

impl<I: Iterator<Item = u64>> WordReader<I> {
    /// A reader over `words`.
    pub fn new(words: I) -> Self {
        WordReader { words }
    }
}

impl<I: Iterator<Item = u64>> StateWords for WordReader<I> {
    fn word(&mut self, w: &mut u64) -> Result<(), CheckpointError> {
        *w = self.words.next().ok_or(CheckpointError::Truncated)?;
        Ok(())
    }
    fn same(&mut self, w: u64, what: &'static str) -> Result<(), CheckpointError> {
        let c = self.words.next().ok_or(CheckpointError::Truncated)?;
        if c != w {
            return Err(CheckpointError::Mismatch {
                what,
                world: w,
                checkpoint: c,
            });
        }
        Ok(())
    }
}

/// A scalar's raw bits.
pub(crate) fn scalar<S: Scalar>(v: &mut impl StateWords, x: &mut S) -> Result<(), CheckpointError> {
    let mut w = x.to_bits();
    v.word(&mut w)?;
    *x = S::from_bits(w);
    Ok(())
}

/// A vector's three raw words.
pub(crate) fn vec3<S: Scalar>(
    v: &mut impl StateWords,
    x: &mut Vec3<S>,
) -> Result<(), CheckpointError> {
    scalar(v, &mut x.x)?;
    scalar(v, &mut x.y)?;
    scalar(v, &mut x.z)
}

pub(crate) fn quat<S: Scalar>(
    v: &mut impl StateWords,
    q: &mut Quat<S>,
) -> Result<(), CheckpointError> {
    for x in [&mut q.w, &mut q.x, &mut q.y, &mut q.z] {
        scalar(v, x)?;
    }
    Ok(())
}

/// A changing count or id, read only up to `below` (exclusive).
pub(crate) fn index(
    v: &mut impl StateWords,
    x: &mut u32,
    below: u64,
    what: &'static str,
) -> Result<(), CheckpointError> {
    let mut w = *x as u64;
    v.word(&mut w)?;
    if w >= below {
        return Err(CheckpointError::Corrupt { what, value: w });
    }
    *x = w as u32;
    Ok(())
}

/// A changing flag (0 or 1).
pub(crate) fn flag(
    v: &mut impl StateWords,
    x: &mut bool,
    what: &'static str,
) -> Result<(), CheckpointError> {
    let mut w = *x as u64;
    v.word(&mut w)?;
    if w > 1 {
        return Err(CheckpointError::Corrupt { what, value: w });
    }
    *x = w == 1;
    Ok(())
}
