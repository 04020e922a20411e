// parse_command_line (see usage_errors.h). Every subcommand allows extras, so unknown options
// and stray words land in remaining() instead of CLI11's "not expected" sentence; they are
// reported first, even when a requirement failed too, because the typo usually caused it.
#include "apps/deepvox/usage_errors.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "core/text.h"

namespace dv::cli {

namespace {

constexpr int kUsageExit = 2;

int usage_error(const std::string& message) {
  std::fprintf(stderr, "deepvox: error: %s\n", message.c_str());
  return kUsageExit;
}

std::string with_suggestion(std::string message, const std::string& word,
                            const std::vector<std::string>& known) {
  const std::string nearest = nearest_word(word, known);
  if (!nearest.empty()) message += "; did you mean '" + nearest + "'?";
  return message;
}

std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  return names;
}

std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
    for (const std::string& n : o->get_snames()) names.push_back("-" + n);
  }
  return names;
}

std::string subcommand_list(const CLI::App& app) {
  std::string list;
  for (const std::string& n : subcommand_names(app)) list += (list.empty() ? "" : ", ") + n;
  return list;
}

// The subcommand argv names (checked known before parsing), or the app itself.
const CLI::App& chosen(const CLI::App& app, int argc, char** argv) {
  if (argc > 1)
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
      if (sub->get_name() == argv[1]) return *sub;
  return app;
}

// "" when nothing was left over; else the message for the first unknown option (the first
// stray word when there is none).
std::string leftover_message(const CLI::App& app, const CLI::App& command) {
  const std::vector<std::string> rest = app.remaining(true);
  if (rest.empty()) return "";
  const std::string where = &command == &app ? "" : command.get_name() + ": ";
  for (const std::string& word : rest)
    if (word.size() > 1 && word[0] == '-') {
      const std::string name = word.substr(0, word.find('='));
      return with_suggestion(where + "unknown option '" + name + "'", name, option_names(command));
    }
  return where + "unexpected argument '" + rest.front() + "'";
}

}  // namespace

int parse_command_line(CLI::App& app, int argc, char** argv) {
  app.allow_extras();
  for (CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    sub->allow_extras();
  if (argc > 1) {
    const std::string first = argv[1];
    const bool help = first == "-h" || first == "--help" || first == "--version";
    if (first.size() > 1 && first[0] == '-' && !help)
      return usage_error(with_suggestion("unknown option '" + first +
                                             "' before the subcommand (one of " +
                                             subcommand_list(app) + ")",
                                         first, option_names(app)));
    const std::vector<std::string> known = subcommand_names(app);
    if (first[0] != '-' && std::find(known.begin(), known.end(), first) == known.end())
      return usage_error(with_suggestion("unknown subcommand '" + first + "'", first, known) +
                         " (subcommands: " + subcommand_list(app) + ")");
  }
  const CLI::App& command = chosen(app, argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --help-all, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const std::string leftover = leftover_message(app, command);
    if (!leftover.empty()) return usage_error(leftover);
    if (&command == &app) return usage_error("a subcommand is required: " + subcommand_list(app));
    return usage_error(command.get_name() + ": " + e.what() + " (see 'deepvox " +
                       command.get_name() + " --help')");
  }
  const std::string leftover = leftover_message(app, command);
  if (!leftover.empty()) return usage_error(leftover);
  return -1;
}

}  // namespace dv::cli
