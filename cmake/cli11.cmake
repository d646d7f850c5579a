# CLI11 (Debian: libcli11-dev, header-only). Provides CLI11::CLI11.
find_package(CLI11 CONFIG REQUIRED)
