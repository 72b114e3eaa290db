# Sharded builds (docs/sharding.md): `vt-tiles --shard I/N` then `vt-merge` must give the
# single-process store byte for byte; wrong shard sets are refused. Each tests/shard/<case>.sh runs
# through tests/cli/run_case.sh (golden stdout, stderr and exit status next to it).
set(VT_SHARD_CASES equal_jpeg equal_png equal_float errors usage make parallel)
foreach(case ${VT_SHARD_CASES})
  add_test(NAME shard_${case}
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/cli/run_case.sh
                   ${CMAKE_CURRENT_SOURCE_DIR}/shard/${case}.sh
                   ${CMAKE_CURRENT_BINARY_DIR}/shard/${case}
                   $<TARGET_FILE:vt-tiles> $<TARGET_FILE:vt-merge> $<TARGET_FILE:vt-info>
                   $<TARGET_FILE:vt-synth-image>)
  set_tests_properties(shard_${case} PROPERTIES LABELS quick TIMEOUT 120)
endforeach()
