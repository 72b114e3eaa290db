# Benchmarks (scripts/bench/): built with the project so that they keep compiling under -Werror and
# the sanitizers, never registered as tests. Run them through scripts/bench/accuracy and
# scripts/bench/decode-throughput.
add_executable(vt-bench-accuracy ../scripts/bench/bench_accuracy.c)
target_link_libraries(vt-bench-accuracy PRIVATE vtformats m)
vt_target_warnings(vt-bench-accuracy)
add_executable(vt-bench-decode ../scripts/bench/bench_decode.c)
target_link_libraries(vt-bench-decode PRIVATE vtformats m)
vt_target_warnings(vt-bench-decode)
