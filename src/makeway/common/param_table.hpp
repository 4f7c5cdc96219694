#pragma once
// A stage's configurable parameters declared once, next to the code that uses them: key, member,
// admissible range and a one-line doc per parameter, in the way a nav2 layer declares its
// parameters with a descriptor. The one table drives the bounds half of the stage's validate(),
// the YAML reader (io/config_sections.cpp), config/default.yaml (`makeway config`, checked
// by a test) and `makeway config --describe`. No YAML here: the library stays free of file formats.
//
// Keys are the members' names; a section that gathers several structs prefixes an included
// struct's keys with its name (`include("ground_", ...)`: `ground_seed` is `ground.seed`). Units
// are in the keys' suffixes (_m, _s, _mps, _deg ...; see param_unit()).
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "makeway/common/name_table.hpp"

namespace makeway {

/// Values a numeric parameter admits: lo..hi, either end open; `infinity`: +inf too (".inf" in
/// YAML: "never" limits).
struct ParamRange {
    double lo = 0.0, hi = 0.0;
    bool lo_open = false, hi_open = false;
    bool infinity = false;

    bool contains(double v) const;
    std::string text() const;  ///< "[0, 2]", "(0, 10)", "[0, 3600] or .inf"
    ParamRange or_infinity() const {
        ParamRange r = *this;
        r.infinity = true;
        return r;
    }
};
/// [lo, hi]
constexpr ParamRange closed(double lo, double hi) { return {lo, hi, false, false, false}; }
/// (lo, hi]
constexpr ParamRange above(double lo, double hi) { return {lo, hi, true, false, false}; }
/// [lo, hi)
constexpr ParamRange below(double lo, double hi) { return {lo, hi, false, true, false}; }
/// (lo, hi)
constexpr ParamRange open(double lo, double hi) { return {lo, hi, true, true, false}; }

/// One of a set of names (an enum written as a word), or a list of such names.
struct ParamChoice {
    std::vector<std::string> names;                 ///< admitted names, in the order to list them
    std::function<std::vector<std::string>()> get;  ///< the current value (one name unless a list)
    std::function<void(const std::vector<std::string>&)> set;  ///< called with admitted names only
    bool list = false;  ///< a list of names ([chair, table]), at least one
};
/// Where one parameter lives in a given Params object, typed for the reader.
using ParamRef = std::variant<double*, int*, std::uint32_t*, std::uint64_t*, bool*, ParamChoice>;

/// "a" for one problem, "3 problems: a; b; c" for several: one line, every problem.
std::string join_problems(const std::vector<std::string>& problems);
/// "a, b or c": the admitted names of a choice, for messages.
std::string join_alternatives(const std::vector<std::string>& names);
/// Throws std::invalid_argument(`what` + ": " + join_problems(problems)) unless there are none
/// (an empty `what`: the problems alone).
void throw_if_problems(const std::vector<std::string>& problems, const std::string& what = {});

/// The unit a key's suffix names ("m" for _m, "m/s" for _mps, ...), "" for none.
std::string param_unit(const std::string& key);
/// A number as the configuration writes it: shortest round trip, ".inf" for infinity.
std::string param_number(double v);

template <class P>
class ParamTable {
  public:
    struct Entry {
        std::string key;  ///< "chair.side_m": a nested mapping
        std::function<ParamRef(P&)> ref;
        ParamRange range;  ///< numbers only
        std::string doc;
        std::string old_key;  ///< still read, with a deprecation warning (empty: none)
    };
    struct Check {
        std::function<bool(const P&)> holds;
        std::string message;  ///< names the keys it relates
    };

    /// A number, integer or flag that is a member of P (or of a struct inside P: `get` returns it).
    template <class T>
    ParamTable& add(std::string key, T P::*member, ParamRange range, std::string doc) {
        return add_ref(
            std::move(key), [member](P& p) -> T& { return p.*member; }, range, std::move(doc));
    }
    ParamTable& add(std::string key, bool P::*member, std::string doc) {
        return add(std::move(key), member, ParamRange{}, std::move(doc));
    }
    template <class Get>
    ParamTable& add_ref(std::string key, Get get, ParamRange range, std::string doc) {
        entries_.push_back({std::move(key),
                            [get](P& p) -> ParamRef { return &get(p); },
                            range,
                            std::move(doc),
                            {}});
        return *this;
    }
    /// An enum written as one of `names`.
    template <class E>
    ParamTable& choice(std::string key, E P::*member, NameTable<E> names, std::string doc) {
        std::vector<std::string> words = names_in(names);
        entries_.push_back({std::move(key),
                            [member, names, words](P& p) -> ParamRef {
                                E& value = p.*member;
                                ParamChoice c;
                                c.names = words;
                                c.get = [&value, names] {
                                    const auto name = name_of(names, value);
                                    return name ? std::vector<std::string>{std::string(*name)}
                                                : std::vector<std::string>{};
                                };
                                c.set = [&value, names](const std::vector<std::string>& chosen) {
                                    if (const auto v = value_named(names, chosen.front()))
                                        value = *v;
                                };
                                return c;
                            },
                            ParamRange{},
                            std::move(doc),
                            {}});
        return *this;
    }
    /// A value of any other shape, as a ParamChoice made for the object (lists of names).
    ParamTable& add_choice(std::string key, std::function<ParamChoice(P&)> make, std::string doc) {
        entries_.push_back({std::move(key),
                            [make](P& p) -> ParamRef { return make(p); },
                            ParamRange{},
                            std::move(doc),
                            {}});
        return *this;
    }
    /// The last entry's key before it was renamed: read for one release, with a warning.
    ParamTable& renamed_from(std::string old_key) {
        entries_.back().old_key = std::move(old_key);
        return *this;
    }
    /// A rule between parameters that no single range says (checked after every range).
    ParamTable& require(std::function<bool(const P&)> holds, std::string message) {
        checks_.push_back({std::move(holds), std::move(message)});
        return *this;
    }
    /// Every entry and rule of `inner`'s table, for the struct `get(p)` returns, keys prefixed.
    template <class Q, class Get>
    ParamTable& include(const std::string& prefix, Get get, const ParamTable<Q>& inner) {
        for (const auto& e : inner.entries()) {
            entries_.push_back({prefix + e.key, [get, ref = e.ref](P& p) { return ref(get(p)); },
                                e.range, e.doc,
                                e.old_key.empty() ? std::string() : prefix + e.old_key});
        }
        // A nested mapping's rules name it ("chair.edge_cost must ..."); a flattened struct's rules
        // name their own keys.
        const bool nested = !prefix.empty() && prefix.back() == '.';
        for (const auto& c : inner.checks()) {
            checks_.push_back(
                {[get, holds = c.holds](const P& p) { return holds(get(const_cast<P&>(p))); },
                 nested ? prefix + c.message : c.message});
        }
        return *this;
    }

    const std::vector<Entry>& entries() const { return entries_; }
    const std::vector<Check>& checks() const { return checks_; }

    /// "key must be in [a, b] (got v)" for each number out of its range, then each rule broken.
    std::vector<std::string> problems(const P& p) const {
        std::vector<std::string> out;
        P& q = const_cast<P&>(p);  // refs are read only here
        for (const auto& e : entries_) {
            const ParamRef r = e.ref(q);
            double v = 0.0;
            if (const auto* d = std::get_if<double*>(&r))
                v = **d;
            else if (const auto* i = std::get_if<int*>(&r))
                v = **i;
            else if (const auto* u = std::get_if<std::uint32_t*>(&r))
                v = static_cast<double>(**u);
            else if (const auto* w = std::get_if<std::uint64_t*>(&r))
                v = static_cast<double>(**w);
            else
                continue;
            if (!e.range.contains(v))
                out.push_back(e.key + " must be in " + e.range.text() + " (got " + param_number(v) +
                              ")");
        }
        for (const auto& c : checks_) {
            if (!c.holds(p)) out.push_back(c.message);
        }
        return out;
    }

  private:
    std::vector<Entry> entries_;
    std::vector<Check> checks_;
};

}  // namespace makeway
