// The CLI's precompiled header: the common one and CLI11, which every command unit parses.
#pragma once
#include "strand_pch.h"
#include <CLI/CLI.hpp>
