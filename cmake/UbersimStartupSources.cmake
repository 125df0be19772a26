# ubersim_startup_only(FILE...): sources that only read a program's command line
# and start it (a main.cpp beside its Shell, the command-line helpers): compiled
# at -O0 in Release. They run once, at start-up, so their optimisation costs only
# build time: CLI11's templates at -O3 took 7-15 s of CPU a file, at -O0 about
# half (README, "What CI runs, and what it costs"). Call it in the folder whose
# CMakeLists.txt adds the target (source properties belong to their folder).
function(ubersim_startup_only)
  set_source_files_properties(${ARGN} PROPERTIES COMPILE_OPTIONS $<$<CONFIG:Release>:-O0>)
endfunction()
