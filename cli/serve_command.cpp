// `strand serve`: flags only; the workbench itself is serve/ (strand_serve).
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "serve/server.h"

namespace strand::cli {

void add_serve_command(CLI::App& app, Action& action) {
  CLI::App* sub = app.add_subcommand(
      "serve", "the workbench: design, preview and keep specimens in a browser (local web app)");
  auto o = std::make_shared<serve::ServeOptions>();
  sub->add_option("--port", o->port, "TCP port; 0 picks a free one (printed) (default 8080)");
  sub->add_option("--host", o->host,
                  "address to listen on (default 127.0.0.1; another needs --token)");
  sub->add_option("--data", o->data_dir,
                  "directory for the saved jobs and their files (default $XDG_DATA_HOME/strand, "
                  "else ~/.local/share/strand)");
  sub->add_option("--token", o->token,
                  "secret every request must carry (header X-Strand-Token, or open /?token=T once)");
  sub->callback([&action, o] { action = [o] { return serve::run_serve(*o, std::cout); }; });
}

}  // namespace strand::cli
