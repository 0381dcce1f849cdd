# The libraries of the WebAssembly build (NBAR_WASM), for emscripten's toolchain: the header-only
# ones from the machine's packages as they are, yaml-cpp compiled for WebAssembly from Debian's
# source package by scripts/build-wasm.sh (NBAR_WASM_YAML_CPP is where it installed it).
if(NOT EMSCRIPTEN)
  message(FATAL_ERROR "NBAR_WASM needs emscripten: configure with emcmake (scripts/build-wasm.sh)")
endif()
set(NBAR_WASM_YAML_CPP "" CACHE PATH "yaml-cpp built for WebAssembly (its install prefix)")
if(NOT EXISTS ${NBAR_WASM_YAML_CPP}/lib/libyaml-cpp.a)
  message(FATAL_ERROR "NBAR_WASM_YAML_CPP=${NBAR_WASM_YAML_CPP} holds no lib/libyaml-cpp.a: build it with scripts/build-wasm.sh")
endif()

# Emscripten must not see the machine's /usr/include (its C library is not the machine's): each
# header-only library is reached through a folder of its own, a link to its folder in /usr/include.
set(NBAR_WASM_HEADERS ${PROJECT_BINARY_DIR}/host-headers)
foreach(folder IN ITEMS fmt nlohmann)
  if(NOT EXISTS /usr/include/${folder})
    message(FATAL_ERROR "/usr/include/${folder} is missing: scripts/install-deps.sh installs it")
  endif()
  file(MAKE_DIRECTORY ${NBAR_WASM_HEADERS})
  file(CREATE_LINK /usr/include/${folder} ${NBAR_WASM_HEADERS}/${folder} SYMBOLIC)
endforeach()

add_library(Eigen3::Eigen INTERFACE IMPORTED)
target_include_directories(Eigen3::Eigen SYSTEM INTERFACE /usr/include/eigen3)
add_library(fmt::fmt INTERFACE IMPORTED)
target_include_directories(fmt::fmt SYSTEM INTERFACE ${NBAR_WASM_HEADERS})
target_compile_definitions(fmt::fmt INTERFACE FMT_HEADER_ONLY)
add_library(nlohmann_json::nlohmann_json INTERFACE IMPORTED)
target_include_directories(nlohmann_json::nlohmann_json SYSTEM INTERFACE ${NBAR_WASM_HEADERS})
add_library(yaml-cpp STATIC IMPORTED)
set_target_properties(yaml-cpp PROPERTIES IMPORTED_LOCATION ${NBAR_WASM_YAML_CPP}/lib/libyaml-cpp.a)
target_include_directories(yaml-cpp SYSTEM INTERFACE ${NBAR_WASM_YAML_CPP}/include)
# One thread: the browser engine runs without shared memory (a static host gives no cross-origin
# isolation), so every thread count of the core is 1 there (the web API's configuration says so).
add_library(Threads::Threads INTERFACE IMPORTED)

# nbar's errors are exceptions: emscripten ignores them unless told (its default is
# -fignore-exceptions), at compile and at link time. WebAssembly's own exception handling (wasm)
# costs nothing until something throws; emscripten's JavaScript unwinding (js) calls every function
# that may throw through JavaScript, which made the engine slower (docs/javascript.md), and is
# only for browsers older than 2022 (Chrome 95, Firefox 100, Safari 15.2). yaml-cpp must be compiled
# the same way (scripts/build-wasm.sh).
set(NBAR_WASM_EXCEPTIONS wasm CACHE STRING "C++ exceptions in WebAssembly: wasm (WebAssembly's exception handling) or js (emscripten's JavaScript unwinding)")
set_property(CACHE NBAR_WASM_EXCEPTIONS PROPERTY STRINGS wasm js)
if(NBAR_WASM_EXCEPTIONS STREQUAL "wasm")
  add_compile_options(-fwasm-exceptions)
  add_link_options(-fwasm-exceptions)
elseif(NBAR_WASM_EXCEPTIONS STREQUAL "js")
  add_compile_options(-fexceptions)
  add_link_options(-fexceptions)
else()
  message(FATAL_ERROR "NBAR_WASM_EXCEPTIONS is wasm or js, not ${NBAR_WASM_EXCEPTIONS}")
endif()
