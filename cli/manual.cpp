#include "cli/manual.h"

#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/version.h"
#include "machines/profile.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"

namespace strand::cli {

namespace {

// Text as roff shows it literally: backslashes and dashes escaped, a leading '.' or '\''
// (a roff request) made plain.
std::string roff(const std::string& text) {
  std::string out;
  bool line_start = true;
  for (const char c : text) {
    if (line_start && (c == '.' || c == '\'')) out += "\\&";
    if (c == '\\') {
      out += "\\e";
    } else if (c == '-') {
      out += "\\-";
    } else {
      out += c;
    }
    line_start = c == '\n';
  }
  return out;
}

std::vector<const CLI::App*> commands_of(const CLI::App& app) {
  return app.get_subcommands([](const CLI::App*) { return true; });
}

std::string upper(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

// "--nozzle" / "-o, --output" as written on the command line.
std::string option_names(const CLI::Option& o) {
  std::string names;
  for (const auto& s : o.get_snames()) names += (names.empty() ? "-" : ", -") + s;
  for (const auto& l : o.get_lnames()) names += (names.empty() ? "--" : ", --") + l;
  return names.empty() ? o.get_name() : names;
}

std::vector<std::string> flags_of(const CLI::App& command) {
  std::vector<std::string> flags;
  for (const auto* o : command.get_options()) {
    for (const auto& s : o->get_snames()) flags.push_back("-" + s);
    for (const auto& l : o->get_lnames()) flags.push_back("--" + l);
  }
  return flags;
}

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : " ") + w;
  return out;
}

}  // namespace

std::string man_page(const CLI::App& app, const CLI::App* command, const std::string& version) {
  const std::string name = command ? "strand-" + command->get_name() : "strand";
  std::string out = ".TH " + upper(roff(name)) + " 1 \"\" \"" + roff(version) +
                    "\" \"Strand manual\"\n.SH NAME\n" + roff(name) + " \\- " +
                    roff(command ? command->get_description() : app.get_description()) + "\n";
  if (!command) {
    out += ".SH SYNOPSIS\n.B strand\n\\fICOMMAND\\fR [\\fIOPTIONS\\fR]\n.SH COMMANDS\n";
    for (const auto* sub : commands_of(app)) {
      out += ".TP\n.B " + roff(sub->get_name()) + "\n" + roff(sub->get_description()) + "\n";
    }
    out +=
        ".SH OPTIONS\n.TP\n.B \\-\\-help\nShow the commands, or a command's flags.\n"
        ".TP\n.B \\-\\-version\nPrint the version and the libraries strand was built with.\n"
        ".TP\n.B \\-\\-quiet\nNo progress on standard error (any command).\n"
        ".TP\n.B \\-\\-progress\nA progress line per phase on standard error from the start "
        "(default: a bar on a terminal, otherwise lines once a run passes one second).\n"
        ".SH UNITS\nLengths in millimetres, speeds in mm/min, angles in degrees. A value may "
        "carry its unit: mm, cm, m, um, in; mm/min, mm/s; deg, rad (0.84mm, 840um, 250mm/s, "
        "36x36mm); it is converted to the unit --help shows, and a unit of another kind is "
        "refused. Page sizes take paper names: A0 to A6, letter, legal, tabloid, portrait "
        "unless landscape is added (A4 landscape). Choices take any case.\n"
        ".SH FILES\nA command that writes one file names it after its input unless \\-o is "
        "given (drawing.svg \\(-> drawing.gcode), and never replaces the input.\n"
        ".SH EXIT STATUS\n.TP\n.B 0\nDone.\n.TP\n.B 1\nA check found problems, or a sweep "
        "point failed.\n.TP\n.B 2\nBad input: one line on standard error naming the "
        "parameter and its allowed range; no output file is written.\n.SH SEE ALSO\n";
    std::string see;
    for (const auto* sub : commands_of(app)) {
      see += (see.empty() ? "" : ",\n") + std::string(".BR strand\\-") + roff(sub->get_name()) +
             " (1)";
    }
    return out + see + "\n";
  }
  out += ".SH SYNOPSIS\n.B strand " + roff(command->get_name()) + "\n";
  for (const auto* o : command->get_options()) {
    if (o->get_positional()) out += "\\fI" + roff(o->get_name()) + "\\fR\n";
  }
  out += "[\\fIOPTIONS\\fR]\n.SH OPTIONS\n";
  for (const auto* o : command->get_options()) {
    out += ".TP\n.B " + roff(option_names(*o));
    if (o->get_type_size() != 0 && !o->get_type_name().empty()) {
      out += " \\fI" + roff(o->get_type_name()) + "\\fR";
    }
    out += "\n" + roff(o->get_description());
    if (o->get_required()) out += " (required)";
    if (!o->get_default_str().empty()) out += " (default: " + roff(o->get_default_str()) + ")";
    out += "\n";
  }
  return out + ".SH SEE ALSO\n.BR strand (1)\n";
}

std::string bash_completion(const CLI::App& app, const std::vector<std::string>& machines) {
  std::vector<std::string> commands;
  std::string cases;
  for (const auto* sub : commands_of(app)) {
    commands.push_back(sub->get_name());
    cases += "    " + sub->get_name() + ") flags='" + joined(flags_of(*sub)) + "' ;;\n";
  }
  return "# bash completion for strand (generated by `strand completion bash`)\n"
         "_strand() {\n"
         "  local cur=\"${COMP_WORDS[COMP_CWORD]}\" prev=\"${COMP_WORDS[COMP_CWORD-1]}\"\n"
         "  local flags=''\n"
         "  if [[ $COMP_CWORD -eq 1 ]]; then\n"
         "    COMPREPLY=($(compgen -W '" +
         joined(commands) +
         " --help --version --quiet --progress' -- \"$cur\"))\n"
         "    return\n"
         "  fi\n"
         "  case \"$prev\" in\n"
         "    --machine) COMPREPLY=($(compgen -W '" +
         joined(machines) +
         "' -- \"$cur\")); return ;;\n"
         "  esac\n"
         "  case \"${COMP_WORDS[1]}\" in\n" +
         cases +
         "  esac\n"
         "  if [[ \"$cur\" == -* ]]; then\n"
         "    COMPREPLY=($(compgen -W \"$flags\" -- \"$cur\"))\n"
         "  else\n"
         "    COMPREPLY=($(compgen -f -- \"$cur\"))\n"
         "  fi\n"
         "}\n"
         "complete -o filenames -F _strand strand\n";
}

std::string zsh_completion(const CLI::App& app, const std::vector<std::string>& machines) {
  return "#compdef strand\n# zsh completion for strand (generated by `strand completion "
         "zsh`): the bash function through zsh's bashcompinit.\n"
         "autoload -U +X bashcompinit && bashcompinit\n" +
         bash_completion(app, machines);
}

void add_manual_commands(CLI::App& app, Action& action) {
  CLI::App* manual = app.add_subcommand(
      "manual", "print the manual page (roff) of strand or of a command, or write them all");
  auto command = std::make_shared<std::string>();
  auto dir = std::make_shared<std::string>();
  manual->add_option("command", *command, "a command (none: strand(1) itself)");
  manual->add_option("--dir", *dir, "write strand.1 and strand-COMMAND.1 for every command here");
  manual->callback([&app, &action, command, dir] {
    action = [&app, command, dir] {
      const std::string version = "strand " + version_number();
      if (!dir->empty()) {
        std::error_code ec;
        std::filesystem::create_directories(*dir, ec);
        if (ec)
          throw InputError("manual.dir = " + *dir + ": cannot create it (" + ec.message() + ")");
        slicer::OutputFiles files;
        files.stage(*dir + "/strand.1", man_page(app, nullptr, version));
        for (const auto* sub : commands_of(app)) {
          files.stage(*dir + "/strand-" + sub->get_name() + ".1", man_page(app, sub, version));
        }
        files.commit();
        return 0;
      }
      if (command->empty()) {
        std::cout << man_page(app, nullptr, version);
        return 0;
      }
      for (const auto* sub : commands_of(app)) {
        if (sub->get_name() == *command) {
          std::cout << man_page(app, sub, version);
          return 0;
        }
      }
      throw InputError("manual: no command '" + *command + "' (strand --help lists them)");
    };
  });
  CLI::App* completion =
      app.add_subcommand("completion", "print the shell completion script (bash or zsh)");
  auto shell = std::make_shared<std::string>();
  completion->add_option("shell", *shell, "bash or zsh")
      ->required()
      ->check(CLI::IsMember({"bash", "zsh"}));
  completion->callback([&app, &action, shell] {
    action = [&app, shell] {
      std::vector<std::string> machines;
      for (const auto& [name, description] : machines::list_profiles()) machines.push_back(name);
      std::cout << (*shell == "zsh" ? zsh_completion(app, machines)
                                    : bash_completion(app, machines));
      return 0;
    };
  });
}

}  // namespace strand::cli
