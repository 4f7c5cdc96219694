#pragma once
// A subcommand, described without the parser. Each cmd_*.cpp holds its option structs, the run
// functions, and one Registration per subcommand saying its name, its options and what runs;
// main.cpp, the only file that includes CLI11 (about 6 s of compile time per file that does),
// collects the registrations and turns the descriptions into its parser. Adding a subcommand is one
// new file and one line in apps/CMakeLists.txt.
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace makeway::apps {

/// Exit codes: 0 success, 1 an internal error, 2 bad input (one line on stderr, nothing written).
constexpr int kExitBadInput = 2;

/// Prints "makeway: MESSAGE" to stderr.
void print_error(const std::string& message);

/// One option or positional argument and the member it fills. Chained setters, in the way CLI11's
/// are, so that a declaration reads as the parser's would.
class OptionSpec {
  public:
    using Target =
        std::variant<std::string*, int*, double*, std::uint64_t*, bool*, std::optional<double>*,
                     std::vector<std::string>*, std::vector<double>*>;
    enum class Path { kAny, kExistingFile, kExistingDirectory };
    /// A check of the text as given: empty when it passes, else what is wrong.
    using Check = std::function<std::string(const std::string&)>;

    OptionSpec(std::string name, Target target, std::string help, bool flag)
        : name_(std::move(name)), help_(std::move(help)), target_(target), flag_(flag) {}

    OptionSpec& required() { return required_ = true, *this; }
    /// The default value appears in --help.
    OptionSpec& show_default() { return show_default_ = true, *this; }
    OptionSpec& choices(std::vector<std::string> admitted) {
        return choices_ = std::move(admitted), *this;
    }
    OptionSpec& range(int lo, int hi) { return range_ = std::pair{lo, hi}, *this; }
    OptionSpec& range(double lo, double hi) { return range_ = std::pair{lo, hi}, *this; }
    OptionSpec& existing_file() { return path_ = Path::kExistingFile, *this; }
    OptionSpec& existing_directory() { return path_ = Path::kExistingDirectory, *this; }
    /// List options: values may also come as one comma-separated word.
    OptionSpec& delimiter(char c) { return delimiter_ = c, *this; }
    /// Values per occurrence: exactly n, or between lo and hi (-1: no upper bound).
    OptionSpec& expected(int n) { return expected_ = std::pair{n, n}, *this; }
    OptionSpec& expected(int lo, int hi) { return expected_ = std::pair{lo, hi}, *this; }
    OptionSpec& excludes(const OptionSpec& other) {
        return excludes_.push_back(other.name_), *this;
    }
    OptionSpec& needs(const OptionSpec& other) { return needs_.push_back(other.name_), *this; }
    /// A file the command writes (besides --out, --out-bag and OUT, which are outputs by name): it
    /// may not name one of the inputs.
    OptionSpec& output() { return output_ = true, *this; }
    /// A check of its own; `what` names it in --help (e.g. "K/N").
    OptionSpec& check(Check check, std::string what) {
        return check_ = std::move(check), check_name_ = std::move(what), *this;
    }

    const std::string& name() const { return name_; }
    const std::string& help() const { return help_; }
    const Target& target() const { return target_; }
    bool is_flag() const { return flag_; }
    bool is_output() const {
        return output_ || name_ == "--out" || name_ == "--out-bag" || name_ == "OUT";
    }
    bool is_required() const { return required_; }
    bool shows_default() const { return show_default_; }
    const std::vector<std::string>& admitted() const { return choices_; }
    const std::variant<std::monostate, std::pair<int, int>, std::pair<double, double>>& bounds()
        const {
        return range_;
    }
    Path path() const { return path_; }
    char list_delimiter() const { return delimiter_; }
    const std::optional<std::pair<int, int>>& value_count() const { return expected_; }
    const std::vector<std::string>& excluded() const { return excludes_; }
    const std::vector<std::string>& needed() const { return needs_; }
    const Check& own_check() const { return check_; }
    const std::string& own_check_name() const { return check_name_; }

  private:
    std::string name_, help_;
    Target target_;
    bool flag_ = false, required_ = false, show_default_ = false, output_ = false;
    std::vector<std::string> choices_;
    std::variant<std::monostate, std::pair<int, int>, std::pair<double, double>> range_;
    Path path_ = Path::kAny;
    char delimiter_ = 0;
    std::optional<std::pair<int, int>> expected_;
    std::vector<std::string> excludes_, needs_;
    Check check_;
    std::string check_name_;
};

/// The options of one subcommand, in the order --help lists them.
class CommandSpec {
  public:
    /// "--name" for an option, "NAME" for a positional argument.
    template <class T>
    OptionSpec& option(std::string name, T& member, std::string help) {
        return options_.emplace_back(std::move(name), &member, std::move(help), false);
    }
    /// "--name" sets the member true; "!--name" sets it false.
    OptionSpec& flag(std::string name, bool& member, std::string help) {
        return options_.emplace_back(std::move(name), &member, std::move(help), true);
    }
    const std::deque<OptionSpec>& options() const { return options_; }

  private:
    std::deque<OptionSpec> options_;  // a deque: the references handed out stay valid
};

/// Where a subcommand is listed in --help.
enum class Group { kSetup, kPointClouds, kSimulation, kRecordedData, kLearning, kEvaluation };
const char* to_string(Group group);

struct Command {
    std::string path;  ///< "info", or "bench nav" for a subcommand of `bench`
    Group group = Group::kSetup;
    std::string help;
    /// Declares the options into fresh storage and returns what runs with them.
    std::function<std::function<int()>(CommandSpec&)> make;
};

void register_command(Command command);
/// Every registered subcommand, by group and then by path.
std::vector<Command> registered_commands();

/// One per subcommand, at namespace scope in its file:
///   const Registration<InfoOptions> kInfo{"info", Group::kPointClouds, "...", declare, run_info};
template <class Options>
struct Registration {
    Registration(std::string path, Group group, std::string help,
                 void (*declare)(CommandSpec&, Options&), int (*run)(const Options&)) {
        register_command({std::move(path), group, std::move(help),
                          [declare, run](CommandSpec& spec) -> std::function<int()> {
                              auto options = std::make_shared<Options>();
                              declare(spec, *options);
                              return [options, run] { return run(*options); };
                          }});
    }
};

}  // namespace makeway::apps
