#include "apps/command.hpp"

#include <algorithm>
#include <iostream>

namespace makeway::apps {
namespace {

// A function-local static: registrations run during static initialisation, in any file order.
std::vector<Command>& registry() {
    static std::vector<Command> commands;
    return commands;
}

}  // namespace

void print_error(const std::string& message) { std::cerr << "makeway: " << message << "\n"; }

const char* to_string(Group group) {
    switch (group) {
        case Group::kSetup:
            return "Start here";
        case Group::kPointClouds:
            return "Point clouds and objects";
        case Group::kSimulation:
            return "Simulation";
        case Group::kRecordedData:
            return "Recorded data";
        case Group::kLearning:
            return "Training";
        case Group::kEvaluation:
            return "Evaluation";
    }
    return "Subcommands";
}

void register_command(Command command) { registry().push_back(std::move(command)); }

std::vector<Command> registered_commands() {
    std::vector<Command> commands = registry();
    std::stable_sort(commands.begin(), commands.end(), [](const Command& a, const Command& b) {
        return std::pair(a.group, a.path) < std::pair(b.group, b.path);
    });
    return commands;
}

}  // namespace makeway::apps
