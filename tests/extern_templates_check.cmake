# Checks that a translation unit built with IMPULSE_EXTERN_TEMPLATES=1 only
# parses the world: its object file defines none of the pipeline's members
# (step, advance, the narrow phase, the solver), which the declaration
# leaves to impulse/instantiate.hpp's file. A member moved back inside its
# class (inline, so compiled wherever it is used) would show up here.
#   cmake -DNM=nm -DOBJECTS="a.o;b.o" -P extern_templates_check.cmake
# With -DPART=scalar_parts, it checks only that the objects define none of
# what depends on the scalar alone: the narrow phase that
# IMPULSE_DECLARE_NARROW_PHASE declares extern, and the solvers' and the
# dynamic BVH's entry points that IMPULSE_DECLARE_SCALAR_PARTS does. The
# case of a file that instantiates a world of its own configuration.
execute_process(COMMAND ${NM} -C --defined-only ${OBJECTS} OUTPUT_VARIABLE symbols RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "nm failed on ${OBJECTS}")
endif()
if(PART STREQUAL "scalar_parts")
  string(REGEX MATCHALL "impulse::narrowphase::(detail::call_collide|time_of_impact|sphere_cast)<[^(]*>\\(" found
    "${symbols}")
  string(REGEX MATCHALL
    "impulse::(basic_sequential_impulse|basic_soft_step|broadphase::basic_dynamic_bvh)<(float|double)>::(solve|prepare|project_joints|update|move|create|destroy)\\("
    found_parts "${symbols}")
  list(APPEND found ${found_parts})
  list(REMOVE_DUPLICATES found)
  if(found)
    message(FATAL_ERROR "compiled in a file that should only parse them: ${found}")
  endif()
  if(NOT symbols MATCHES "impulse::world<")
    message(FATAL_ERROR "no world compiled in ${OBJECTS}: the check checks nothing")
  endif()
  message(STATUS "a world compiled, none of the default shapes' narrow phase, the solvers or the dynamic BVH")
  return()
endif()
set(found)
foreach(member IN ITEMS step advance update_contacts collide solve continuous update_sleep create_joint ray_cast)
  if(symbols MATCHES "impulse::world<[^\n]*>::${member}\\(")
    list(APPEND found ${member})
  endif()
endforeach()
if(found)
  message(FATAL_ERROR "compiled in a file that should only parse the world: world::${found}")
endif()
string(REGEX MATCHALL "\n[0-9a-f]* [TW] " defined "${symbols}")
list(LENGTH defined count)
message(STATUS "no pipeline member compiled; ${count} small functions defined (create_body's shape part, math)")
