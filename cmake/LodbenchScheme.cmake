# lodbench_add_scheme(<target> SOURCES <c++ files...> [SHADERS <shader files...>])
#
# A scheme plugin (docs/plugins.md): a MODULE library of SOURCES that lodbench loads with --plugin
# or a config's "plugins". Each shader (.vert, .tesc, .comp, .task, .mesh; a .tese once per
# partitioning mode, as lodbench's own) is compiled at build time with glslangValidator, its own folder and lodbench's
# shared shader includes on the include path, and its SPIR-V is linked into the library: a shader
# error fails the build with the compiler's message, the plugin is one file, and that file's digest
# (in every case's identity) covers its shaders too.
#
# Used by lodbench's package config (installed) and by lodbench's own build (its test plugins);
# either sets LODBENCH_GLSLANG_VALIDATOR, LODBENCH_SHADER_INCLUDE_DIR, LODBENCH_PLUGINS and the
# target lodbench::scheme_api first.
set(_LODBENCH_EMBED_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/lodbench_embed_spirv.cmake")

function(lodbench_add_scheme target)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "" "SOURCES;SHADERS")
  if(ARG_UNPARSED_ARGUMENTS OR NOT ARG_SOURCES)
    message(FATAL_ERROR "lodbench_add_scheme(${target} SOURCES <c++ files> [SHADERS <shader files>]): "
                        "unexpected '${ARG_UNPARSED_ARGUMENTS}' or no SOURCES")
  endif()
  if(NOT LODBENCH_PLUGINS)
    message(FATAL_ERROR "lodbench_add_scheme(${target}): this lodbench cannot load plugins: ${LODBENCH_PLUGINS_OFF_REASON}")
  endif()
  if(NOT LODBENCH_GLSLANG_VALIDATOR)
    message(FATAL_ERROR "lodbench_add_scheme(${target}): glslangValidator not found (Debian: apt-get install glslang-tools)")
  endif()
  file(GLOB shared_includes ${LODBENCH_SHADER_INCLUDE_DIR}/*.glsl ${LODBENCH_SHADER_INCLUDE_DIR}/*.h)
  set(spv_dir ${CMAKE_CURRENT_BINARY_DIR}/${target}_spirv)
  file(MAKE_DIRECTORY ${spv_dir})
  set(spv_files)
  foreach(src IN LISTS ARG_SHADERS)
    get_filename_component(src ${src} ABSOLUTE)
    get_filename_component(dir ${src} DIRECTORY)
    get_filename_component(name ${src} NAME)
    get_filename_component(stem ${src} NAME_WE)
    get_filename_component(ext ${src} LAST_EXT)
    file(GLOB own_includes ${dir}/*.glsl ${dir}/*.h)
    # The renderer loads <stem>_<partitioning>.tese.spv (render/scheme.h partitioningName).
    if(ext STREQUAL ".tese")
      set(outs ${stem}_integer.tese.spv ${stem}_fractional_even.tese.spv ${stem}_fractional_odd.tese.spv)
      set(spacings equal_spacing fractional_even_spacing fractional_odd_spacing)
    elseif(ext MATCHES "^\\.(vert|tesc|comp|task|mesh)$")
      set(outs ${name}.spv)
      set(spacings "")
    else()
      message(FATAL_ERROR "lodbench_add_scheme(${target}): ${src}: a scheme's shaders are .vert, .tesc, .tese, .comp, .task or .mesh "
                          "(the fragment and histogram stages are lodbench's own)")
    endif()
    foreach(out IN LISTS outs)
      set(defs)
      if(spacings)
        list(POP_FRONT spacings spacing)
        set(defs -DSPACING=${spacing})
      endif()
      add_custom_command(OUTPUT ${spv_dir}/${out}
        COMMAND ${LODBENCH_GLSLANG_VALIDATOR} -V --target-env vulkan1.2 -I${dir} -I${LODBENCH_SHADER_INCLUDE_DIR}
                ${defs} -o ${spv_dir}/${out} ${src}
        DEPENDS ${src} ${shared_includes} ${own_includes}
        COMMENT "glslang ${src} -> ${out}" VERBATIM)
      list(APPEND spv_files ${spv_dir}/${out})
    endforeach()
  endforeach()
  # '|' for ';': a list would split the custom command's argument.
  string(REPLACE ";" "|" files_arg "${spv_files}")
  set(table ${CMAKE_CURRENT_BINARY_DIR}/${target}_shaders.cpp)
  add_custom_command(OUTPUT ${table}
    COMMAND ${CMAKE_COMMAND} -DOUT=${table} -DFILES=${files_arg} -P ${_LODBENCH_EMBED_SCRIPT}
    DEPENDS ${spv_files} ${_LODBENCH_EMBED_SCRIPT}
    COMMENT "lodbench: ${target}'s SPIR-V -> ${target}_shaders.cpp" VERBATIM)
  add_library(${target} MODULE ${ARG_SOURCES} ${table})
  target_link_libraries(${target} PRIVATE lodbench::scheme_api)
  # The plugin's own definitions win over same-named ones lodbench exports (its lb:: symbols).
  target_link_options(${target} PRIVATE LINKER:-Bsymbolic)
endfunction()
