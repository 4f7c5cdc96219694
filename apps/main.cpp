// makeway: the command-line front end. Turns the subcommands that the cmd_*.cpp files register
// (apps/command.hpp) into CLI11's parser, refuses bad numbers and outputs over inputs, and runs
// the chosen one.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <type_traits>
#include <variant>

#include "apps/command.hpp"
#include "io/error.hpp"
#include "io/interrupt.hpp"
#include "io/staged_output.hpp"

namespace {

using namespace makeway::apps;

// Subcommands that only group others (`makeway bench nav`): their line in --help.
const std::map<std::string, std::string> kParents{{"bench", "Benchmarks that print JSON"}};

// One option of a subcommand's description, as CLI11 takes it.
CLI::Option* add_option(CLI::App& sub, const OptionSpec& spec) {
    CLI::Option* o = std::visit(
        [&](auto* member) -> CLI::Option* {
            if constexpr (std::is_same_v<decltype(member), bool*>) {
                if (spec.is_flag()) return sub.add_flag(spec.name(), *member, spec.help());
            }
            return sub.add_option(spec.name(), *member, spec.help());
        },
        spec.target());
    if (spec.is_required()) o->required();
    if (spec.list_delimiter() != 0) o->delimiter(spec.list_delimiter());
    if (spec.value_count()) o->expected(spec.value_count()->first, spec.value_count()->second);
    if (const auto* r = std::get_if<std::pair<int, int>>(&spec.bounds()))
        o->check(CLI::Range(r->first, r->second));
    if (const auto* r = std::get_if<std::pair<double, double>>(&spec.bounds()))
        o->check(CLI::Range(r->first, r->second));
    if (!spec.admitted().empty()) o->check(CLI::IsMember(spec.admitted()));
    if (spec.path() == OptionSpec::Path::kExistingFile) o->check(CLI::ExistingFile);
    if (spec.path() == OptionSpec::Path::kExistingDirectory) o->check(CLI::ExistingDirectory);
    if (spec.own_check()) {
        o->check(
            CLI::Validator([check = spec.own_check()](std::string& text) { return check(text); },
                           spec.own_check_name()));
    }
    if (spec.shows_default()) o->capture_default_str();
    return o;
}

// Every registered subcommand into `app`; what runs for each of them into `runs`, the options that
// name outputs into `outputs`.
void add_commands(CLI::App& app, std::map<const CLI::App*, std::function<int()>>& runs,
                  std::set<const CLI::Option*>& outputs) {
    std::map<std::string, CLI::App*> parents;
    for (const Command& command : registered_commands()) {
        CLI::App* parent = &app;
        std::string name = command.path;
        if (const auto space = name.find(' '); space != std::string::npos) {
            const std::string group = name.substr(0, space);
            name = name.substr(space + 1);
            CLI::App*& made = parents[group];
            if (made == nullptr) {
                made = app.add_subcommand(group, kParents.at(group));
                made->group(to_string(command.group));
                made->require_subcommand(1);
            }
            parent = made;
        }
        CLI::App* sub = parent->add_subcommand(name, command.help);
        // CLI11 hands a parent's group down: `bench`'s own list keeps the plain heading.
        sub->group(parent == &app ? to_string(command.group) : "Subcommands");
        CommandSpec spec;
        runs[sub] = command.make(spec);
        for (const OptionSpec& option : spec.options()) {
            const CLI::Option* added = add_option(*sub, option);
            if (option.is_output()) outputs.insert(added);
        }
        for (const OptionSpec& option : spec.options()) {
            for (const std::string& other : option.excluded())
                sub->get_option(option.name())->excludes(sub->get_option(other));
            for (const std::string& other : option.needed())
                sub->get_option(option.name())->needs(sub->get_option(other));
        }
    }
}

// Every number at the boundary: a FLOAT option must be finite (CLI11 reads "nan" and "inf" as
// numbers, and a NaN passes a Range check), an unsigned one must be written as a whole number that
// fits (CLI11 saturates "-1" and "1e23" to 2^64-1).
void check_numbers(CLI::App& app) {
    const CLI::Validator finite(
        [](std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            return end != text.c_str() && !std::isfinite(v) ? "must be a finite number" : "";
        },
        "", "finite");
    const CLI::Validator whole(
        [](std::string& text) -> std::string {
            if (text.empty() || !std::all_of(text.begin(), text.end(),
                                             [](unsigned char c) { return std::isdigit(c); })) {
                return "must be a non-negative whole number";
            }
            errno = 0;
            (void)std::strtoull(text.c_str(), nullptr, 10);
            return errno == ERANGE ? "is too large (at most 18446744073709551615)" : "";
        },
        "", "whole");
    for (CLI::Option* o : app.get_options()) {
        const std::string type = o->get_type_name();
        if (type.rfind("FLOAT", 0) == 0) o->check(finite);
        if (type.rfind("UINT", 0) == 0) o->check(whole);
    }
    for (CLI::App* sub : app.get_subcommands({})) check_numbers(*sub);
}

// Every path option of the chosen subcommand: outputs and the inputs (any other value naming
// something that exists), for refuse_outputs_over_inputs.
void collect_paths(const CLI::App& app, const std::set<const CLI::Option*>& output_options,
                   std::vector<std::pair<std::string, std::string>>& outputs,
                   std::vector<std::pair<std::string, std::string>>& inputs) {
    for (const CLI::Option* o : app.get_options()) {
        if (o->count() == 0) continue;
        const std::string name = o->get_name();
        for (const std::string& value : o->results()) {
            std::error_code ec;
            if (output_options.count(o) != 0)
                outputs.emplace_back(name, value);
            else if (std::filesystem::exists(value, ec))
                inputs.emplace_back(name, value);
        }
    }
    for (const CLI::App* sub : app.get_subcommands())
        collect_paths(*sub, output_options, outputs, inputs);
}

}  // namespace

int main(int argc, char** argv) {
    makeway::io::install_interrupt_handlers();
    CLI::App app{
        "makeway: object-aware affordance costmaps for proactive indoor navigation "
        "with a 3D LiDAR"};
    app.set_version_flag("--version", "makeway 0.1.0");
    app.set_help_all_flag("--help-all", "Print the help of every subcommand and exit");
    app.require_subcommand(1);
    std::map<const CLI::App*, std::function<int()>> runs;
    std::set<const CLI::Option*> output_options;
    add_commands(app, runs, output_options);
    check_numbers(app);
    if (argc > 1 && argv[1][0] != '-') {
        bool known = false;
        for (const CLI::App* sub : app.get_subcommands({})) known |= sub->get_name() == argv[1];
        if (!known) {
            print_error(std::string("unknown subcommand '") + argv[1] + "' (see makeway --help)");
            return kExitBadInput;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        print_error(e.what());
        return kExitBadInput;
    }
    try {
        std::vector<std::pair<std::string, std::string>> outputs, inputs;
        collect_paths(app, output_options, outputs, inputs);
        makeway::io::refuse_outputs_over_inputs(
            outputs, inputs);  // before any work: no output replaces an input
        // The subcommand chosen, down to the leaf (`bench nav`).
        const CLI::App* chosen = &app;
        while (!chosen->get_subcommands().empty()) chosen = chosen->get_subcommands().front();
        const int rc = runs.at(chosen)();
        // A result that never reached its reader (a full disk, a closed pipe) is not a success.
        std::cout.flush();
        if (!std::cout || std::fflush(stdout) != 0) {
            print_error("standard output: write failed");
            return kExitBadInput;
        }
        return rc;
    } catch (const makeway::io::FileError& e) {
        print_error(e.what());
        return kExitBadInput;
    } catch (const makeway::io::Interrupted& e) {
        print_error(e.what());
        return e.exit_code();
    } catch (const std::exception& e) {
        const std::string what = e.what();
        print_error("internal error: " +
                    what.substr(0, what.find('\n')));  // one line (torch appends backtraces)
        return 1;
    }
    return 1;
}
