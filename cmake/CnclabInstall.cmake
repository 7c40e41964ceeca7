# `cmake --install build --prefix P`: the cnclab executable in P/bin, and under
# P/share/cnclab everything it reads at run time, laid out as in the
# repository (an installed cnclab finds them from its own place:
# src/cnclab/core/share_paths.hpp):
#   configs/             shared configs (surfaces, machines, trainers, datasets, studies)
#   experiments/         the studies' experiment files (the tables find their results by them)
#   results/reference/   the papers' numbers, transcribed
#   scripts/figures/     the figure scripts (SHARE/scripts/figures/run RESULTS_DIR)
#   scripts/optuna/      the Optuna helper of model-based sweeps (sweep/optuna_helper.hpp)
#   templates/project/   what `cnclab init DIR` copies
# `cpack -G DEB` in the build folder packages the same as a .deb.
include(GNUInstallDirs)
set(CNCLAB_SHARE_INSTALL_DIR ${CMAKE_INSTALL_DATADIR}/cnclab)

install(TARGETS cnclab RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY configs experiments templates DESTINATION ${CNCLAB_SHARE_INSTALL_DIR})
install(DIRECTORY results/reference DESTINATION ${CNCLAB_SHARE_INSTALL_DIR}/results)
install(DIRECTORY scripts/figures scripts/optuna DESTINATION ${CNCLAB_SHARE_INSTALL_DIR}/scripts
        USE_SOURCE_PERMISSIONS PATTERN "__pycache__" EXCLUDE)
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})

# The .deb: its dependencies are the shared libraries cnclab links (HDF5,
# yaml-cpp, Ipopt, ...) as dpkg-shlibdeps finds them, and Python with the
# packages the figure scripts import (recommended: cnclab runs without them).
set(CPACK_PACKAGE_NAME cnclab)
set(CPACK_PACKAGE_VENDOR "cnclab")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Experiments, datasets and paper tables for neural-network studies of CNC machining error")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "cnclab maintainers <cnclab@localhost>")
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
    "python3, python3-matplotlib, python3-h5py, python3-numpy, python3-yaml, python3-optuna, python3-cmaes, python3-sklearn")
set(CPACK_GENERATOR DEB)
include(CPack)
