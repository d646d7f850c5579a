# nlohmann-json 3 (Debian: nlohmann-json3-dev, header-only). Provides nlohmann_json::nlohmann_json.
find_package(nlohmann_json 3 CONFIG REQUIRED)
