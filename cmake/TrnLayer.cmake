# trn_add_layer(NAME INCLUDE_DIR dir [PUBLIC targets...] [PRIVATE targets...])
# One layer of the trnkit library stack (docs/ARCHITECTURE.md, "Layers"): sources go into the
# OBJECT library trnkit_NAME_objects (hidden visibility, PIC), which the shared library
# trnkit_NAME (trnkit::NAME) is linked from. Only declarations between TRN_API_BEGIN/END in the
# public headers are exported (trn/export.hpp). In-tree tests that reach into a layer's internal
# headers link trnkit_NAME_objects instead of the shared library. PUBLIC: the layers below that
# the public headers need; PRIVATE: implementation-only dependencies (never seen by consumers).
function(trn_add_layer name)
  cmake_parse_arguments(L "" "INCLUDE_DIR" "PUBLIC;PRIVATE" ${ARGN})
  set(objects trnkit_${name}_objects)
  add_library(${objects} OBJECT)
  set_target_properties(${objects} PROPERTIES POSITION_INDEPENDENT_CODE ON CXX_VISIBILITY_PRESET hidden
                                              VISIBILITY_INLINES_HIDDEN ON)
  target_include_directories(${objects} PUBLIC $<BUILD_INTERFACE:${L_INCLUDE_DIR}>)
  target_link_libraries(${objects} PUBLIC ${L_PUBLIC} PRIVATE trn_options ${L_PRIVATE})

  add_library(trnkit_${name} SHARED)
  add_library(trnkit::${name} ALIAS trnkit_${name})
  target_link_libraries(trnkit_${name} PRIVATE ${objects} PUBLIC ${L_PUBLIC})
  target_include_directories(trnkit_${name} PUBLIC $<BUILD_INTERFACE:${L_INCLUDE_DIR}>
                                                   $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  # The public headers use C++20 (<span>, designated initialisers): consumers get it from the target.
  target_compile_features(trnkit_${name} PUBLIC cxx_std_20)
  # Installed libraries find each other in their own folder.
  set_target_properties(trnkit_${name} PROPERTIES VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}
                                                  EXPORT_NAME ${name} INSTALL_RPATH "$ORIGIN")
  set_property(GLOBAL APPEND PROPERTY TRN_LAYERS trnkit_${name})
endfunction()
