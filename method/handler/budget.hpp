#pragma once
/// A time budget for one simulation step of collision handling, polled only
/// at interruption points (the paper).
///
/// Three kinds: unlimited; wall clock (milliseconds from the budget's
/// creation, on an injectable clock so tests never sleep); work units (each
/// task charges its fixed cost, work_units.hpp; reproducible on any machine).
/// Work is counted under every kind, so steps.csv always reports it.
/// expired() is true once the spent wall time or work reaches the budget; a
/// budget of 0 is expired from the start (the cycle still runs one task a
/// step: with the paper's granularity, a new cycle's hashing of all tets).
/// The granularity the budget saw: max_task_work() is the largest single
/// charge (one task's work; a whole cycle for methods that charge it at
/// once), and for wall budgets max_poll_gap_ms() the longest interval between
/// two polls of expired(), the first measured from the budget's creation.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>

namespace tcb {

/// Milliseconds on some monotonic clock.
using ClockMs = std::function<double()>;
ClockMs steady_clock_ms();

enum class BudgetKind { None, WallMs, Work };

class Budget {
 public:
  using Kind = BudgetKind;

  static Budget unlimited() { return Budget(Kind::None, 0.0, {}); }
  static Budget wall_ms(double budget_ms, ClockMs clock = steady_clock_ms()) {
    Budget b(Kind::WallMs, budget_ms, std::move(clock));
    b.m_start_ms = b.m_last_poll_ms = b.m_clock();
    return b;
  }
  static Budget work_units(std::uint64_t units) { return Budget(Kind::Work, static_cast<double>(units), {}); }

  bool expired() const {
    switch (m_kind) {
      case Kind::None: return false;
      case Kind::Work: return static_cast<double>(m_spent) >= m_limit;
      case Kind::WallMs: {
        const double now = m_clock();
        m_last_gap_ms = now - m_last_poll_ms;
        m_max_gap_ms = std::max(m_max_gap_ms, m_last_gap_ms);
        m_last_poll_ms = now;
        ++m_polls;
        return now - m_start_ms >= m_limit;
      }
    }
    return false;
  }
  void charge(std::uint64_t units) {
    m_spent += units;
    m_max_charge = std::max(m_max_charge, units);
  }
  std::uint64_t max_task_work() const { return m_max_charge; }
  /// Wall budgets: milliseconds since the budget's creation (0 for other
  /// kinds). Not a poll: it does not count in max_poll_gap_ms().
  double elapsed_ms() const { return m_kind == Kind::WallMs ? m_clock() - m_start_ms : 0.0; }
  /// Wall budgets: lowers the limit by `ms` (>= 0), for work the caller
  /// still has to do after the last poll. No effect on other kinds.
  void reserve_ms(double ms) {
    if (m_kind == Kind::WallMs && ms > 0.0) m_limit -= ms;
  }
  /// Wall budgets only (0 before the first poll and for other kinds).
  double max_poll_gap_ms() const { return m_max_gap_ms; }
  /// Wall budgets: the interval between the last two polls of expired() (the
  /// first from the budget's creation), that is, the last task's time when
  /// polled after every task; 0 before the first poll and for other kinds.
  double last_poll_gap_ms() const { return m_last_gap_ms; }
  /// Wall budgets: whether a task of `task_ms` started at the last poll
  /// would end past the limit. Reads no clock (the last poll's time stands
  /// for now); false for other kinds.
  bool would_overrun(double task_ms) const {
    return m_kind == Kind::WallMs && m_polls > 0 && m_last_poll_ms - m_start_ms + task_ms > m_limit;
  }
  /// How often expired() read the wall clock (wall budgets; 0 for others).
  std::uint64_t polls() const { return m_polls; }
  std::uint64_t spent() const { return m_spent; }
  Kind kind() const { return m_kind; }
  double limit() const { return m_limit; }

 private:
  Budget(Kind kind, double limit, ClockMs clock) : m_kind(kind), m_limit(limit), m_clock(std::move(clock)) {}
  Kind m_kind;
  double m_limit;
  ClockMs m_clock;
  double m_start_ms = 0.0;
  std::uint64_t m_spent = 0, m_max_charge = 0;
  mutable double m_last_poll_ms = 0.0, m_max_gap_ms = 0.0, m_last_gap_ms = 0.0;
  mutable std::uint64_t m_polls = 0;
};

/// The largest work budget: 2^53 units, the last integer a double (the
/// spec's value) holds exactly together with all below it.
inline constexpr double kMaxWorkBudget = 9007199254740992.0;

/// The number grammar of budget labels: a plain decimal >= 0 (digits and at
/// most one point; no sign, exponent or blanks) filling all of `text`;
/// std::nullopt otherwise.
std::optional<double> parse_budget_number(const std::string& text);

/// `value` (finite, >= 0) in the grammar above: its shortest round-trip form
/// when that has no exponent, else positional digits (17 after the point).
std::string plain_decimal(double value);

/// A budget as asked for, before any step: its kind and value, its one text
/// form, and the Budget each step starts from. The text forms are "none",
/// "ms:X" (X >= 0 milliseconds of wall clock) and "work:N" (N whole work
/// units); they name budgets in sweeps, thresholds, summary.csv and run.json.
struct BudgetSpec {
  BudgetKind kind = BudgetKind::None;
  double value = 0.0;  ///< milliseconds, or work units (a whole number)

  /// std::nullopt for anything but the three forms above (negative, not
  /// finite, a fractional work count, trailing text).
  static std::optional<BudgetSpec> parse(const std::string& text);
  /// The text form; parse(label()) gives the same spec back (for wall
  /// budgets below 1e-4 ms written with 17 decimals: equal to 1e-17 ms).
  std::string label() const;
  /// "none", "wall_ms" or "work": run.json's budget.kind.
  std::string kind_name() const;
  /// A fresh budget for one step.
  Budget start() const;
};

}  // namespace tcb
