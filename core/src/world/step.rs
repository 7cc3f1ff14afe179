//! The step: the stages of [`crate::step`] in order, with the contact, bond and integration
//! stages split into parts that a [`Parallel`] runner may run on several threads.

use super::World;
use crate::body::BodyForce;
use crate::error::StepError;
use crate::num::Scalar;
use crate::step::bonds::{prepare, remove_broken, BondPart, BondShared, Clock, MIN_BONDS_PER_PART};
use crate::step::integration::IntegratePart;
use crate::step::multirate::Cycle;
use crate::step::narrow_phase::{ContactPart, Shared};
use crate::step::parts::{hull, split_ranges, Parallel, Serial, MAX_PARTS};
use crate::step::wall_motion::move_walls;
use crate::wall::MAX_WALLS;
use core::ops::Range;

/// The force sums one extra thread of a threaded step writes for bodies outside its own
/// range: as long as the body arena, all zero between steps (the step leaves it so).
pub type ThreadScratch<'s, S> = &'s mut [BodyForce<S>];

/// One range per part, for at most N parts.
type Ranges<const N: usize> = heapless::Vec<Range<usize>, N>;

/// Each part's items, their count and its measured time ([`crate::step::balance`]).
type Measured<const N: usize> = heapless::Vec<(Range<usize>, u64, u64), N>;

/// The time each of a stage's `jobs` parts took, as `par` measured it, when the step may
/// cut by it: two parts or more, in fixed point (an `f64` sum depends on the cuts, so `f64`
/// keeps its cuts by count; [`crate::step::balance`]).
fn part_times<S: Scalar, P: Parallel, const N: usize>(par: &P, jobs: usize) -> Option<[u64; N]> {
    let mut times = [0u64; N];
    (jobs > 1 && S::Q32_32 && par.job_times(&mut times[..jobs])).then_some(times)
}

/// The parts `ranges` of a stage with their counts, where `count_before(i)` counts items
/// `0..i`, and their measured `times`.
fn measured<const N: usize>(
    ranges: &[Range<usize>],
    times: &[u64],
    count_before: impl Fn(usize) -> u64,
) -> Measured<N> {
    ranges
        .iter()
        .zip(times)
        .map(|(r, &t)| (r.clone(), count_before(r.end) - count_before(r.start), t))
        .collect()
}

impl<S: Scalar> World<'_, S> {
    /// Advance the world by one time step on the calling thread.
    ///
    /// Errors: [`StepError::NoTimeStep`], [`StepError::TimeStepTooLarge`] (checked before any
    /// state changes), [`StepError::Overflow`] naming the stage and bodies,
    /// [`StepError::ContactCapacity`], [`StepError::UndefinedPair`]. After an error other than
    /// the time-step ones the state is partly advanced.
    pub fn step(&mut self) -> Result<(), StepError> {
        self.step_with(&Serial, &mut [])
    }

    /// Run `n` steps on the calling thread, stopping at the first error.
    pub fn run(&mut self, n: u64) -> Result<(), StepError> {
        for _ in 0..n {
            self.step()?;
        }
        Ok(())
    }

    /// Advance the world by one time step, with the contact and integration stages split into
    /// `par.parts()` parts (at most one per usable `scratch` arena, each
    /// [`ThreadScratch`]) that `par` may run at the same time. In fixed point the result is
    /// the same bits for any number of parts. Errors as [`World::step`].
    pub fn step_with<P: Parallel>(
        &mut self,
        par: &P,
        scratch: &mut [ThreadScratch<'_, S>],
    ) -> Result<(), StepError> {
        if self.dt_s == 0.0 {
            return Err(StepError::NoTimeStep);
        }
        let max_s = self.max_timestep_s();
        if self.dt_s > max_s {
            return Err(StepError::TimeStepTooLarge {
                dt_s: self.dt_s,
                max_s,
            });
        }
        if let Some((dt_s, max_s)) = self.long_step_excess() {
            return Err(StepError::TimeStepTooLarge { dt_s, max_s });
        }
        let result = self.stages(par, scratch);
        if result.is_err() {
            // Leave no partial sums behind for the next step.
            let nb = self.n_bodies as usize;
            self.forces[..nb].fill(BodyForce::default());
            for arena in scratch.iter_mut() {
                let len = arena.len().min(nb);
                arena[..len].fill(BodyForce::default());
            }
        }
        result
    }

    fn stages<P: Parallel>(
        &mut self,
        par: &P,
        scratch: &mut [ThreadScratch<'_, S>],
    ) -> Result<(), StepError> {
        let nb = self.n_bodies as usize;
        let ns = self.n_spheres as usize;
        if self.air_drag.on {
            self.air_drag.apply(
                &self.bodies[..nb],
                &self.spheres[..ns],
                &mut self.forces[..nb],
            )?;
        }
        self.list
            .ensure(&self.spheres[..ns], &self.walls, self.max_radius, par)?;
        // One part per usable scratch arena, when the runner has threads for them.
        let usable = scratch.iter().filter(|a| a.len() >= nb).count();
        let parts = if par.parts() > 1 {
            par.parts().min(usable)
        } else {
            1
        }
        .max(1);
        let max_disp = if parts == 1 {
            self.staged::<P, 1, 2>(par, parts, scratch)?
        } else {
            self.staged::<P, MAX_PARTS, { MAX_PARTS + 1 }>(par, parts, scratch)?
        };
        self.list.note_drift(max_disp);
        let wall_disp = move_walls(&mut self.walls, self.dt)?;
        if wall_disp != S::ZERO {
            self.list.note_drift(wall_disp);
        }
        self.time += self.dt;
        self.steps += 1;
        Ok(())
    }

    /// The contact, bond and integration stages in `parts` ≤ N parts, with room for N parts
    /// and for SUMS accumulator arenas per integration part (N + 1). Returns the largest
    /// sphere displacement, mm.
    ///
    /// Why sized: the job lists live on the stack, and at [`MAX_PARTS`] they take about
    /// 200 kB (an integration part alone holds room for 65 arenas). A one-part step of a
    /// small world (the one-sphere rigs of a diagnosis run millions of them) spent most of
    /// its time touching that frame, page by page. `#[inline(never)]` keeps each size's
    /// frame to itself.
    #[inline(never)]
    fn staged<P: Parallel, const N: usize, const SUMS: usize>(
        &mut self,
        par: &P,
        parts: usize,
        scratch: &mut [ThreadScratch<'_, S>],
    ) -> Result<S, StepError> {
        let cycle = Cycle::at(self.steps, self.slow_stride, self.dt);
        let mut touched = self.contact_stage::<P, N>(par, parts, scratch, &cycle)?;
        self.bond_stage::<P, N>(par, parts, scratch, &mut touched)?;
        self.integration_stage::<P, N, SUMS>(par, parts, scratch, &touched, &cycle)
    }

    /// The first sphere of body `b` (the sphere count for `b` = the body count).
    fn first_sphere_of(&self, b: usize) -> usize {
        if b < self.n_bodies as usize {
            self.bodies[b].first_sphere as usize
        } else {
            self.n_spheres as usize
        }
    }

    /// The contact stage in `parts` parts over body ranges of about equal entry counts.
    /// Returns, per part, the bodies beyond its range whose sums it wrote in its scratch
    /// arena.
    fn contact_stage<P: Parallel, const N: usize>(
        &mut self,
        par: &P,
        parts: usize,
        scratch: &mut [ThreadScratch<'_, S>],
        cycle: &Cycle<S>,
    ) -> Result<Ranges<N>, StepError> {
        let nb = self.n_bodies as usize;
        let ns = self.n_spheres as usize;
        let mut ranges = Ranges::<N>::new();
        {
            let offsets = self.list.live().offsets;
            let entries_before = |b: usize| offsets[self.first_sphere_of(b)] as u64;
            let balance = if cycle.is_slow_contact_step() {
                &self.balance.slow_contacts
            } else {
                &self.balance.contacts
            };
            let weights = balance.weights(nb, &entries_before);
            split_ranges(nb, parts, |b| weights.before(b), |_| true, &mut ranges);
        }
        let sphere_ranges: Ranges<N> = ranges
            .iter()
            .map(|r| self.first_sphere_of(r.start)..self.first_sphere_of(r.end))
            .collect();
        let live = self.list.live_mut();
        let shared = Shared {
            bodies: &self.bodies[..nb],
            spheres: &self.spheres[..ns],
            pairs: &self.pairs,
            walls: &self.walls,
            bonded: self.bond_table.pairs(),
            offsets: live.offsets,
            dt: self.dt,
            cycle: *cycle,
            slow_pairs: false,
        };
        let mut jobs: heapless::Vec<ContactPart<'_, S>, N> = heapless::Vec::new();
        {
            let mut entries = &mut live.entries[..];
            let mut effects = &mut live.effects[..];
            let mut own = &mut self.forces[..nb];
            let mut consumed_entries = 0usize;
            let mut usable = scratch.iter_mut().filter(|a| a.len() >= nb);
            for (bodies, spheres) in ranges.iter().zip(sphere_ranges.iter()) {
                let end = live.offsets[spheres.end] as usize;
                let (e, rest) = core::mem::take(&mut entries).split_at_mut(end - consumed_entries);
                entries = rest;
                let (f, rest_f) = if effects.is_empty() {
                    (&mut [][..], &mut [][..])
                } else {
                    core::mem::take(&mut effects).split_at_mut(end - consumed_entries)
                };
                effects = rest_f;
                consumed_entries = end;
                let (o, rest_o) = core::mem::take(&mut own).split_at_mut(bodies.len());
                own = rest_o;
                let beyond: &mut [BodyForce<S>] = if parts > 1 {
                    usable.next().map(|a| &mut a[..nb]).unwrap_or(&mut [])
                } else {
                    &mut []
                };
                let _ = jobs.push(ContactPart {
                    spheres: spheres.clone(),
                    bodies: bodies.clone(),
                    entries: e,
                    effects: f,
                    own: o,
                    beyond,
                    beyond_touched: 0..0,
                    wall_force: [BodyForce::default(); MAX_WALLS],
                    result: Ok(()),
                });
            }
        }
        par.for_each(&mut jobs, &|part: &mut ContactPart<'_, S>| {
            part.run(&shared)
        });
        let times = part_times::<S, P, N>(par, jobs.len());
        let mut touched = Ranges::<N>::new();
        let mut wall_sums = [BodyForce::<S>::default(); MAX_WALLS];
        for part in jobs.iter() {
            part.result?;
            let _ = touched.push(part.beyond_touched.clone());
            for (sum, f) in wall_sums.iter_mut().zip(part.wall_force.iter()) {
                sum.merge(f);
            }
        }
        drop(jobs);
        if let Some(times) = times {
            let offsets = self.list.live().offsets;
            let parts = measured::<N>(&ranges, &times, |b| offsets[self.first_sphere_of(b)] as u64);
            let balance = if cycle.is_slow_contact_step() {
                &mut self.balance.slow_contacts
            } else {
                &mut self.balance.contacts
            };
            balance.record(nb, parts.iter().cloned());
        }
        for (w, sum) in self.walls.iter_mut().zip(wall_sums.iter()) {
            w.force = sum.force();
        }
        Ok(touched)
    }

    /// The bond stage in at most `parts` parts over runs of about equal bond counts (one part
    /// below [`MIN_BONDS_PER_PART`] bonds a part). Part 0 adds into the world's accumulators,
    /// part k > 0 into the k-th scratch arena, and `touched[k]` grows to cover what it wrote.
    fn bond_stage<P: Parallel, const N: usize>(
        &mut self,
        par: &P,
        parts: usize,
        scratch: &mut [ThreadScratch<'_, S>],
        touched: &mut Ranges<N>,
    ) -> Result<(), StepError> {
        let nb = self.n_bodies as usize;
        let ns = self.n_spheres as usize;
        let clock = Clock {
            step: self.steps,
            time: self.time,
            dt_s: self.dt_s,
        };
        let table = &mut self.bond_table;
        if !prepare(table, &self.spheres[..ns], &self.bodies[..nb], &clock)? {
            return Ok(());
        }
        let n = table.n as usize;
        // Where each part adds its loads: the world's accumulators, then usable scratch
        // arenas 1, 2, … (arena k is the one contact part k wrote, see `touched`).
        let mut sinks: heapless::Vec<&mut [BodyForce<S>], N> = heapless::Vec::new();
        let _ = sinks.push(&mut self.forces[..nb]);
        if parts > 1 {
            for arena in scratch.iter_mut().filter(|a| a.len() >= nb).skip(1) {
                let _ = sinks.push(&mut arena[..nb]);
            }
        }
        let mut ranges = Ranges::<N>::new();
        let bond_parts = parts.min(sinks.len()).min(n / MIN_BONDS_PER_PART).max(1);
        {
            let count_before = |i: usize| i as u64;
            let weights = self.balance.bonds.weights(n, &count_before);
            split_ranges(n, bond_parts, |i| weights.before(i), |_| true, &mut ranges);
        }
        let shared = BondShared {
            sets: &table.sets,
            spheres: &self.spheres[..ns],
            bodies: &self.bodies[..nb],
            dt: self.dt,
        };
        let mut jobs: heapless::Vec<BondPart<'_, S>, N> = heapless::Vec::new();
        let mut bonds = &mut table.bonds[..n];
        for (r, forces) in ranges.iter().zip(sinks) {
            let (mine, rest) = core::mem::take(&mut bonds).split_at_mut(r.len());
            bonds = rest;
            let _ = jobs.push(BondPart {
                bonds: mine,
                forces,
                touched: 0..0,
                breaks: 0,
                result: Ok(()),
            });
        }
        if jobs.len() > 1 {
            par.for_each(&mut jobs, &|part: &mut BondPart<'_, S>| part.run(&shared));
        } else {
            jobs.iter_mut().for_each(|part| part.run(&shared));
        }
        let times = part_times::<S, P, N>(par, jobs.len());
        let mut breaks = 0u64;
        for (k, part) in jobs.iter().enumerate() {
            part.result?;
            breaks += part.breaks as u64;
            if k > 0 {
                while touched.len() <= k {
                    let _ = touched.push(0..0);
                }
                touched[k] = hull(touched[k].clone(), part.touched.clone());
            }
        }
        drop(jobs);
        if let Some(times) = times {
            let parts = measured::<N>(&ranges, &times, |i| i as u64);
            self.balance.bonds.record(n, parts.iter().cloned());
        }
        if breaks > 0 {
            remove_broken(&mut self.bond_table, &clock);
        }
        Ok(())
    }

    /// The integration stage in `parts` parts over body ranges of about equal sphere counts;
    /// `touched[p]` is the range contact part p wrote in its scratch arena. Returns the
    /// largest sphere displacement, mm.
    fn integration_stage<P: Parallel, const N: usize, const SUMS: usize>(
        &mut self,
        par: &P,
        parts: usize,
        scratch: &mut [ThreadScratch<'_, S>],
        touched: &Ranges<N>,
        cycle: &Cycle<S>,
    ) -> Result<S, StepError> {
        let nb = self.n_bodies as usize;
        let ns = self.n_spheres as usize;
        let mut ranges = Ranges::<N>::new();
        {
            let spheres_before = |b: usize| self.first_sphere_of(b) as u64;
            let balance = if cycle.is_slow_move_step() {
                &self.balance.slow_integration
            } else {
                &self.balance.integration
            };
            let weights = balance.weights(nb, &spheres_before);
            split_ranges(nb, parts, |b| weights.before(b), |_| true, &mut ranges);
        }
        let sphere_starts: heapless::Vec<usize, N> = ranges
            .iter()
            .map(|r| self.first_sphere_of(r.start))
            .collect();
        let slow_runs: &[Range<usize>] = if cycle.multirate() {
            self.slow_runs.of(&self.bodies[..nb])
        } else {
            &[]
        };
        let mut jobs: heapless::Vec<IntegratePart<'_, S, SUMS>, N> = heapless::Vec::new();
        {
            let mut bodies = &mut self.bodies[..nb];
            let mut spheres = &mut self.spheres[..ns];
            let mut own = &mut self.forces[..nb];
            // Each contact part's scratch arena, cut down to what it touched, then split below.
            let mut beyond: heapless::Vec<(usize, &mut [BodyForce<S>]), N> = heapless::Vec::new();
            let usable = scratch.iter_mut().filter(|a| a.len() >= nb);
            for (arena, t) in usable.zip(touched.iter()) {
                if !t.is_empty() {
                    let _ = beyond.push((t.start, &mut arena[t.clone()]));
                }
            }
            for (k, r) in ranges.iter().enumerate() {
                let (b, rest) = core::mem::take(&mut bodies).split_at_mut(r.len());
                bodies = rest;
                let sphere_end = if k + 1 < ranges.len() {
                    sphere_starts[k + 1]
                } else {
                    ns
                };
                let (s, rest) =
                    core::mem::take(&mut spheres).split_at_mut(sphere_end - sphere_starts[k]);
                spheres = rest;
                let (o, rest) = core::mem::take(&mut own).split_at_mut(r.len());
                own = rest;
                let mut sums = heapless::Vec::new();
                let _ = sums.push((r.clone(), o));
                for (start, arena) in beyond.iter_mut() {
                    // The part of this arena (covering `start..`) that falls in `r`.
                    let lo = r.start.max(*start);
                    let hi = r.end.min(*start + arena.len());
                    if lo < hi {
                        let (head, tail) = core::mem::take(arena).split_at_mut(hi - *start);
                        *arena = tail;
                        let skip = lo - *start;
                        *start = hi;
                        let _ = sums.push((lo..hi, &mut head[skip..]));
                    }
                }
                let _ = jobs.push(IntegratePart {
                    first_body: r.start,
                    bodies: b,
                    first_sphere: sphere_starts[k],
                    spheres: s,
                    sums,
                    slow_runs,
                    max_disp: S::ZERO,
                    result: Ok(()),
                });
            }
        }
        let (dt, g) = (self.dt, self.gravity);
        par.for_each(&mut jobs, &|part: &mut IntegratePart<'_, S, SUMS>| {
            part.run(dt, g, cycle)
        });
        let times = part_times::<S, P, N>(par, jobs.len());
        let mut max_disp = S::ZERO;
        for part in jobs.iter() {
            part.result?;
            max_disp = max_disp.max(part.max_disp);
        }
        drop(jobs);
        if let Some(times) = times {
            let parts = measured::<N>(&ranges, &times, |b| self.first_sphere_of(b) as u64);
            let balance = if cycle.is_slow_move_step() {
                &mut self.balance.slow_integration
            } else {
                &mut self.balance.integration
            };
            balance.record(nb, parts.iter().cloned());
        }
        Ok(max_disp)
    }
}

#[cfg(test)]
mod tests {
    use crate::num::Fx;
    use crate::owned::{OwnedStorage, OwnedThreadScratch};
    use crate::scenario::BenchBed;
    use crate::step::parts::Parallel;

    /// Runs two parts one after the other and reports the first as taking three times as
    /// long as the second.
    struct FirstPartSlow;

    impl Parallel for FirstPartSlow {
        fn parts(&self) -> usize {
            2
        }
        fn for_each<J: Send>(&self, jobs: &mut [J], f: &(dyn Fn(&mut J) + Sync)) {
            jobs.iter_mut().for_each(f);
        }
        fn job_times(&self, out: &mut [u64]) -> bool {
            for (k, t) in out.iter_mut().enumerate() {
                *t = if k == 0 { 3_000 } else { 1_000 };
            }
            true
        }
    }

    /// The measured times move the cuts: after the first part of every stage was reported
    /// slow for a while, the bodies of the lower half weigh more than those of the upper half
    /// in the contact and integration stages. The bits are those of a one-part step.
    #[test]
    fn reported_times_move_the_cuts_and_no_bit() {
        let bed = BenchBed {
            particles: 600,
            seed: 5,
        };
        let steps = 8_000;
        let mut arenas = OwnedStorage::<Fx>::new(bed.storage_lengths());
        let mut serial = bed.build(arenas.storage()).unwrap();
        serial.run(steps).unwrap();

        let mut arenas = OwnedStorage::<Fx>::new(bed.storage_lengths());
        let mut w = bed.build(arenas.storage()).unwrap();
        let mut scratch = OwnedThreadScratch::<Fx>::new(2, w.bodies().len());
        for _ in 0..steps {
            w.step_with(&FirstPartSlow, &mut scratch.arenas()).unwrap();
        }
        assert_eq!(w.digest(), serial.digest());
        assert!(w.contact_count() > 50, "the bed should be in contact");

        let nb = w.n_bodies as usize;
        let offsets = w.list.live().offsets;
        let entries_before = |b: usize| offsets[w.first_sphere_of(b)] as u64;
        let spheres_before = |b: usize| w.first_sphere_of(b) as u64;
        let contacts = w.balance.contacts.weights(nb, &entries_before);
        let integration = w.balance.integration.weights(nb, &spheres_before);
        // Weight per unit of count, lower half against upper half: at least 1.5 (it starts
        // at 1, every unit weighing the same).
        let halves = |before: &dyn Fn(usize) -> u64, count: &dyn Fn(usize) -> u64| {
            let (w_lo, w_hi) = (before(nb / 2), before(nb) - before(nb / 2));
            let (c_lo, c_hi) = (count(nb / 2), count(nb) - count(nb / 2));
            (w_lo as u128 * c_hi as u128, w_hi as u128 * c_lo as u128)
        };
        for (stage, (lower, upper)) in [
            ("contacts", halves(&|b| contacts.before(b), &entries_before)),
            (
                "integration",
                halves(&|b| integration.before(b), &spheres_before),
            ),
        ] {
            assert!(2 * lower > 3 * upper, "{stage}: {lower} against {upper}");
        }
    }
}
