# `cmake --install BUILD [--prefix P]`: the three programs into P/bin, the
# deployment files and configurations into P/share/animat and the guides
# into P/share/doc/animat, as deploy/systemd/ and deploy/k8s/ expect
# (default prefix /usr/local).
include(GNUInstallDirs)
install(TARGETS animat animat-master animat-worker
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/configs/
  DESTINATION ${CMAKE_INSTALL_DATADIR}/animat/configs)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/deploy/
  DESTINATION ${CMAKE_INSTALL_DATADIR}/animat/deploy
  USE_SOURCE_PERMISSIONS)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/
  DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${PROJECT_SOURCE_DIR}/deploy/systemd/README.md
  DESTINATION ${CMAKE_INSTALL_DOCDIR}/deploy/systemd)
