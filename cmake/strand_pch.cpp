// The unit that builds the shared precompiled headers (cmake/strand_pch.h, strand_cli_pch.h).
