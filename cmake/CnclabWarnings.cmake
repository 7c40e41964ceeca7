# Warnings for cnclab's own targets only (never for third-party headers, which
# are included as SYSTEM through their imported targets).
add_library(cnclab_warnings INTERFACE)
target_compile_options(cnclab_warnings INTERFACE -Wall -Wextra -Wpedantic)
