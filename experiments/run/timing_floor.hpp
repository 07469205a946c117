#pragma once
/// The machine's own overshoot under a wall-clock budget, measured beside a
/// run: a null handler that does nothing but poll the steady clock until the
/// window has passed, then stops, as an interruptible handler stops at its
/// first poll past the budget. Its tasks are a clock read (about 35 ns on the
/// development VM) on no data, so its overshoot is what the machine adds:
/// timer and other interrupts, hypervisor exits, preemption. A stall that
/// covers the deadline is overshoot whatever the method, and the deadline falls
/// in a stall with a probability its length weights, so the p99 of this
/// overshoot, over as many windows as the run has steps, is the floor under
/// the run's overshoot p99 (docs/contract.md, timing).

namespace tcb {

/// Spins on the calling thread for `window_ms` (ms, >= 0) of steady-clock time
/// and returns how far past the window its last clock read landed (ms, >= 0).
/// 0 without spinning for a window that is not positive (or NaN).
double null_handler_overshoot_ms(double window_ms);

}  // namespace tcb
