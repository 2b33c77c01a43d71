#include <rrlab/sweep/sweep_fallback.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <tuple>

namespace rrlab::sweep {

namespace {

using Bits = std::vector<std::uint64_t>;

size_t count(const Bits& a) {
  size_t n = 0;
  for (std::uint64_t w : a) n += size_t(std::popcount(w));
  return n;
}

// One option: a first choice alone (b < 0) or with a fallback.
struct Option {
  int a = 0, b = -1;
  size_t cases = 0, solved = 0, first_solved = 0;
  double cost = 0;  // +inf when a step time is unknown, so it sorts last
};

// Better option first: share solved, cost, one configuration before two, order.
bool preferred(const Option& x, const Option& y) {
  const size_t lhs = x.solved * y.cases, rhs = y.solved * x.cases;  // x.solved / x.cases against y's
  if (lhs != rhs) return lhs > rhs;
  if (x.cost != y.cost) return x.cost < y.cost;
  if ((x.b < 0) != (y.b < 0)) return x.b < 0;
  return std::tie(x.a, x.b) < std::tie(y.a, y.b);
}

double known(double step_us) { return std::isfinite(step_us) ? step_us : INFINITY; }

// gen:FAMILY:SEED:INDEX or perturb:NAME:SEED:INDEX, read from the right.
struct GeneratedKey {
  bool ok = false;
  std::string source;  // gen:FAMILY or perturb:NAME
  std::uint64_t seed = 0, index = 0;
};

bool whole(const std::string& text, std::uint64_t& value) {
  if (text.empty() || text.size() > 19 || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return false;
  value = std::stoull(text);
  return true;
}

GeneratedKey parse_key(const std::string& key) {
  GeneratedKey k;
  if (!key.starts_with("gen:") && !key.starts_with("perturb:")) return k;
  const size_t last = key.rfind(':');
  const size_t before = last == std::string::npos || last == 0 ? std::string::npos : key.rfind(':', last - 1);
  if (before == std::string::npos || key.find(':') == before) return k;
  k.ok = whole(key.substr(last + 1), k.index) && whole(key.substr(before + 1, last - before - 1), k.seed);
  k.source = key.substr(0, before);
  return k;
}

// By generator, its seed and the case's index (numerically), then run seed;
// scenario files by name.
bool listed_before(const CaseRef& x, const CaseRef& y) {
  const GeneratedKey kx = parse_key(x.scenario_key), ky = parse_key(y.scenario_key);
  if (kx.ok && ky.ok)
    return std::tie(kx.source, kx.seed, kx.index, x.seed) < std::tie(ky.source, ky.seed, ky.index, y.seed);
  if (kx.ok != ky.ok) return kx.ok;
  return std::tie(x.scenario_key, x.seed) < std::tie(y.scenario_key, y.seed);
}

// A word for the shell: as it is when plain, else single-quoted.
std::string shell_word(const std::string& word) {
  const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-' || c == '/';
  });
  if (plain) return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

FamilyFallback family_fallback(const FamilyOutcomes& outcomes) {
  FamilyFallback f;
  const size_t total = outcomes.configs.size(), considered = std::min(total, kMaxFallbackConfigs);
  f.configs_total = total;
  f.configs_considered = considered;
  const size_t words = (outcomes.cases.size() + 63) / 64;
  std::vector<Bits> solved(considered, Bits(words, 0)), ran(considered, Bits(words, 0));
  std::vector<CaseRef> unsolved;
  bool witness_ran = false;
  size_t witness_solves = 0;
  for (size_t c = 0; c < outcomes.cases.size(); ++c) {
    const FamilyOutcomes::Case& one = outcomes.cases[c];
    bool any_ran = false, any_solved = false;
    for (size_t i = 0; i < one.outcome.size() && i < total; ++i) {
      any_ran |= one.outcome[i] >= 0;
      any_solved |= one.outcome[i] > 0;
      if (i >= considered || one.outcome[i] < 0) continue;
      ran[i][c / 64] |= std::uint64_t{1} << (c % 64);
      if (one.outcome[i] > 0) solved[i][c / 64] |= std::uint64_t{1} << (c % 64);
    }
    witness_ran |= one.witness >= 0;
    if (!any_ran) continue;
    ++f.cases;
    if (any_solved) {
      ++f.solved_by_some;
      continue;
    }
    unsolved.push_back({one.scenario_key, one.seed});
    witness_solves += one.witness > 0 ? 1 : 0;
  }
  f.unsolved = unsolved.size();
  if (witness_ran) f.witness_solves = witness_solves;
  std::sort(unsolved.begin(), unsolved.end(), listed_before);
  // a case unsolved under several run seeds (a spec's "seeds"): its keys repeat, so each names its seed
  for (size_t i = 1; i < unsolved.size(); ++i) f.several_seeds |= unsolved[i].scenario_key == unsolved[i - 1].scenario_key;
  if (unsolved.size() > kMaxUnsolvedListed) unsolved.resize(kMaxUnsolvedListed);
  f.unsolved_listed = std::move(unsolved);

  std::optional<Option> best;
  const auto offer = [&](const Option& o) {
    if (o.cases > 0 && (!best || preferred(o, *best))) best = o;
  };
  Bits both(words), either(words);
  for (size_t a = 0; a < considered; ++a) {
    const size_t cases_a = count(ran[a]), solved_a = count(solved[a]);
    offer({int(a), -1, cases_a, solved_a, solved_a, known(outcomes.step_us[a])});
    for (size_t b = 0; b < considered; ++b) {
      if (b == a) continue;
      for (size_t w = 0; w < words; ++w) {
        both[w] = ran[a][w] & ran[b][w];
        either[w] = (solved[a][w] | solved[b][w]) & both[w];
      }
      Option o{int(a), int(b), count(both), count(either), 0, 0};
      if (o.cases == 0) continue;
      for (size_t w = 0; w < words; ++w) either[w] = solved[a][w] & both[w];
      o.first_solved = count(either);
      const double a_fails = double(o.cases - o.first_solved) / double(o.cases);
      o.cost = known(outcomes.step_us[a]) + known(outcomes.step_us[b]) * a_fails;
      if (a_fails == 0) o.cost = known(outcomes.step_us[a]);  // B never runs (and inf * 0 is NaN)
      offer(o);
    }
  }
  if (!best) return f;
  f.first = outcomes.configs[size_t(best->a)];
  if (best->b >= 0) f.second = outcomes.configs[size_t(best->b)];
  f.pair_cases = best->cases;
  f.first_solved = best->first_solved;
  f.pair_solved = best->solved;
  f.cost_us = std::isfinite(best->cost) ? best->cost : NAN;
  return f;
}

std::vector<std::string> unsolved_commands(const FamilyFallback& fallback) {
  std::vector<std::string> commands;
  std::string source, indices;
  std::uint64_t seed = 0, last_index = 0;
  const auto flush = [&] {
    if (source.empty()) return;
    const bool perturb = source.starts_with("perturb:");
    const std::string name = source.substr(source.find(':') + 1);
    const std::string out = "unsolved/" + name + "-seed" + std::to_string(seed);
    commands.push_back(std::string("rrlab generate ") + (perturb ? "--perturb " : "") + shell_word(name) + " --seed " +
                       std::to_string(seed) + " --cases " + indices + " --out " + shell_word(out));
    source.clear();
  };
  for (const CaseRef& ref : fallback.unsolved_listed) {
    const GeneratedKey key = parse_key(ref.scenario_key);
    if (!key.ok) continue;
    if (key.source != source || key.seed != seed) {
      flush();
      source = key.source;
      seed = key.seed;
      indices = std::to_string(key.index);
    } else if (key.index != last_index) {  // the same case under another run seed: once
      indices += "," + std::to_string(key.index);
    }
    last_index = key.index;
  }
  flush();
  return commands;
}

}  // namespace rrlab::sweep
