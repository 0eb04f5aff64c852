#pragma once
/// The lockbox_replay program as a library call (docs/replay.md, "A game's own tool"): info,
/// verify, diff and bisect for every game registered in a GameRegistry. The built-in
/// lockbox_replay registers the library scenes and scene files (and a record command); a game
/// registers its own game and gets the same commands in a program of a few lines:
///
///     int main(int argc, char** argv) {
///         lockbox::replay::GameRegistry games;
///         games.Add("mygame", [](const lockbox::replay::ToolGameRequest&, std::string&) {
///             return std::make_unique<MyToolGame>();
///         });
///         return lockbox::replay::RunTool(argc, argv, games, "mygame_replay");
///     }
///
/// The registry is an ordinary object the program fills before the call: no static
/// registration, so no initialisation-order hazard.

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lockbox/dynamics/World.h"
#include "lockbox/replay/Game.h"
#include "lockbox/replay/ReplayFile.h"

namespace lockbox::replay {

/// A game made for one replay: the world and the Game a Player steps. The world must hold the
/// game's initial bodies as the recording program built them (the seed restores in place,
/// keeping their addresses), or be empty.
class ToolGame {
public:
    virtual ~ToolGame() = default;
    virtual b2World& World() = 0;
    virtual Game& Logic() = 0;
};

/// What a factory is asked to build.
struct ToolGameRequest {
    const ReplayFile& file;  ///< the parsed, validated replay (gameName, gameParams, header)
    std::string path;        ///< the replay's path, for messages
    /// Values of the registry's options (AddOption) given on the command line, by option name.
    std::map<std::string, std::string> options;
};

/// Builds the game for a replay; on failure returns nullptr and sets `error` to one line
/// (printed after nothing else, so it should name the file).
using ToolGameFactory = std::function<std::unique_ptr<ToolGame>(const ToolGameRequest& request, std::string& error)>;

/// A command of the program beyond info, verify, diff and bisect (the built-in tool's record).
/// `argv[0]` is the command's name and the rest its arguments; returns the exit code.
using ToolCommandRun = std::function<int(int argc, char** argv)>;

/// The games (and extra options and commands) a replay tool knows.
class GameRegistry {
public:
    /// Replays whose game name (META) is exactly `gameName`.
    void Add(std::string gameName, ToolGameFactory make);
    /// Replays whose game name starts with `prefix` (e.g. "scene:"), after every exact name.
    void AddPrefix(std::string prefix, ToolGameFactory make);
    /// An option with a value for verify, diff and bisect, e.g. "--scene-file" "FILE.json"; its
    /// value reaches every factory in ToolGameRequest::options.
    void AddOption(std::string option, std::string valueName);
    /// A command of its own; `usage` is its line of the usage text (without the program name).
    void AddCommand(std::string name, std::string usage, ToolCommandRun run);
    /// Lines `info` prints after the game's name for the replays a game knows (e.g. a scene
    /// file's hash); `describe` returns "" for others.
    void AddInfo(std::function<std::string(const ReplayFile& file)> describe);

    /// The game for `request.file`: the exact name's factory, else the longest matching
    /// prefix's. nullptr and `error` set when none is registered or the factory refused.
    std::unique_ptr<ToolGame> Make(const ToolGameRequest& request, std::string& error) const;

    struct Command {
        std::string name, usage;
        ToolCommandRun run;
    };
    struct Option {
        std::string name, valueName;
    };
    const std::vector<Command>& Commands() const noexcept { return m_commands; }
    const std::vector<Option>& Options() const noexcept { return m_options; }
    const std::vector<std::function<std::string(const ReplayFile&)>>& Infos() const noexcept { return m_infos; }

private:
    std::map<std::string, ToolGameFactory> m_exact;
    std::map<std::string, ToolGameFactory> m_prefixes;
    std::vector<Option> m_options;
    std::vector<Command> m_commands;
    std::vector<std::function<std::string(const ReplayFile&)>> m_infos;
};

/// Runs the replay tool on the command line `argc`/`argv` (argv[1] is the command) with the
/// games of `games`; `program` names it in messages and the usage text. Commands: info FILE,
/// verify FILE, diff A B, bisect FILE [--inject FRAME:STAGE], the registry's own commands, and
/// the registry's options for verify, diff and bisect. Exit codes: 0 success (verify matched,
/// diff found no difference, bisect found no divergence), 1 a divergence or difference, 2 a
/// usage error, a file that cannot be read, or a game not registered.
int RunTool(int argc, char** argv, const GameRegistry& games, const std::string& program = "lockbox_replay");

}  // namespace lockbox::replay
