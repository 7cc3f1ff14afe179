//! Which build of the lane kernel runs: the same code compiled for the instruction sets this
//! processor has (AVX-512, AVX2), chosen once at run time, or the portable build. All builds
//! compute the same integer function, so they give the same bits (tested below).

use super::{law, LaneBatch, LaneLoads};
use core::sync::atomic::{AtomicU8, Ordering};

/// An instruction set the kernel is built for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Isa {
    /// Any processor.
    Portable,
    /// x86-64 with AVX2, BMI2 and LZCNT (four 64-bit lanes per vector).
    Avx2,
    /// x86-64 with AVX-512 F, DQ, CD, BW and VL (eight 64-bit lanes per vector).
    Avx512,
}

/// The detected set, cached: 0 not yet detected, else 1 + the index in [`Isa::ALL`].
static DETECTED: AtomicU8 = AtomicU8::new(0);

impl Isa {
    /// Every build, from the most portable.
    pub const ALL: [Isa; 3] = [Isa::Portable, Isa::Avx2, Isa::Avx512];

    /// The best build this processor and operating system can run.
    pub fn detected() -> Isa {
        match DETECTED.load(Ordering::Relaxed) {
            0 => {
                let isa = detect();
                let index = Isa::ALL.iter().position(|&i| i == isa).unwrap_or(0);
                DETECTED.store(index as u8 + 1, Ordering::Relaxed);
                isa
            }
            k => Isa::ALL[(k - 1) as usize],
        }
    }

    /// Whether this processor can run the build.
    pub fn available(self) -> bool {
        match (self, Isa::detected()) {
            (Isa::Portable, _) => true,
            (Isa::Avx2, best) => best != Isa::Portable,
            (Isa::Avx512, best) => best == Isa::Avx512,
        }
    }
}

#[cfg(target_arch = "x86_64")]
fn detect() -> Isa {
    use core::arch::x86_64::{__cpuid, __cpuid_count, CpuidResult};
    let bit = |r: u32, b: u32| r & (1 << b) != 0;
    #[allow(unused_unsafe)]
    // SAFETY: `cpuid` exists on every x86-64 processor.
    let (l1, l7, ext): (CpuidResult, CpuidResult, CpuidResult) =
        unsafe { (__cpuid(1), __cpuid_count(7, 0), __cpuid(0x8000_0001)) };
    // The operating system must save the vector registers (OSXSAVE, then XCR0).
    if !(bit(l1.ecx, 27) && bit(l1.ecx, 28)) {
        return Isa::Portable;
    }
    // SAFETY: OSXSAVE is set (checked above), so `xgetbv` is available.
    let xcr0 = unsafe { xcr0() };
    let ymm = xcr0 & 0b110 == 0b110;
    let zmm = xcr0 & 0b1110_0110 == 0b1110_0110;
    let avx2 = ymm && bit(l7.ebx, 5) && bit(l7.ebx, 8) && bit(ext.ecx, 5);
    let avx512 = avx2 && zmm && [16, 17, 28, 30, 31].iter().all(|&b| bit(l7.ebx, b));
    if avx512 {
        Isa::Avx512
    } else if avx2 {
        Isa::Avx2
    } else {
        Isa::Portable
    }
}

/// XCR0, the register of the vector state the operating system saves.
///
/// # Safety
/// The processor must support `xgetbv` (CPUID.1:ECX.OSXSAVE).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "xsave")]
unsafe fn xcr0() -> u64 {
    core::arch::x86_64::_xgetbv(0)
}

#[cfg(not(target_arch = "x86_64"))]
fn detect() -> Isa {
    Isa::Portable
}

/// The kernel, portable build.
pub fn evaluate_portable(b: &LaneBatch, dt: i64) -> LaneLoads {
    law::evaluate(b, dt)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,bmi2,lzcnt")]
fn evaluate_avx2(b: &LaneBatch, dt: i64) -> LaneLoads {
    law::evaluate(b, dt)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,bmi2,lzcnt,avx512f,avx512dq,avx512cd,avx512bw,avx512vl")]
fn evaluate_avx512(b: &LaneBatch, dt: i64) -> LaneLoads {
    law::evaluate(b, dt)
}

/// The kernel ([`super`]) on the contacts of `b` with time step `dt` (raw Q32.32 ms), in the
/// build `isa` when this processor can run it, else the portable one. Every build gives the
/// same bits.
pub fn evaluate_with(isa: Isa, b: &LaneBatch, dt: i64) -> LaneLoads {
    #[cfg(target_arch = "x86_64")]
    if isa.available() {
        match isa {
            // SAFETY: `available` checked that this processor runs these instructions.
            Isa::Avx512 => return unsafe { evaluate_avx512(b, dt) },
            // SAFETY: as above.
            Isa::Avx2 => return unsafe { evaluate_avx2(b, dt) },
            Isa::Portable => {}
        }
    }
    let _ = isa;
    evaluate_portable(b, dt)
}

/// The kernel in the best build this processor runs ([`Isa::detected`]).
pub fn evaluate(b: &LaneBatch, dt: i64) -> LaneLoads {
    evaluate_with(Isa::detected(), b, dt)
}
