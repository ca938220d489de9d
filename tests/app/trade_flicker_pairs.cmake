# `lantern trade --flicker-pairs N`: the flicker is averaged over the run's last N consecutive
# frame pairs, each listed in trade.json (the references', the warps' compared pixels and every
# row's four flicker figures per pair, all positive), and a pair's figures do not depend on how
# many pairs are averaged: the run's last pair measured alone (--flicker-pairs 1) gives the same
# numbers as the last of three (same frames, same references, deterministic renders).
include(${CMAKE_CURRENT_LIST_DIR}/trade_run.cmake)
# JSON paths, keys separated by '|' (a ';' would split the list).
set(lists "flicker|reference_per_pair" "flicker|motion_compensated|reference_per_pair"
  "flicker|motion_compensated|compared_pixels_per_pair" "rows|0|flicker_per_pair|raw"
  "rows|0|flicker_per_pair|denoised" "rows|0|flicker_per_pair|mc_raw"
  "rows|0|flicker_per_pair|mc_denoised")
foreach(n 3 1)
  run_trade("${COMMAND} --flicker-pairs ${n}" ${WORK}_${n} json_${n})
  string(JSON pairs GET "${json_${n}}" flicker pairs)
  if(NOT pairs EQUAL n)
    message(FATAL_ERROR "--flicker-pairs ${n}: trade.json says ${pairs} pairs")
  endif()
  math(EXPR last "${n} - 1")
  foreach(path IN LISTS lists)
    string(REPLACE "|" " " shown "${path}")
    string(REPLACE "|" "_" key "${path}")
    string(REPLACE "|" ";" keys "${path}")
    string(JSON length LENGTH "${json_${n}}" ${keys})
    if(NOT length EQUAL n)
      message(FATAL_ERROR "--flicker-pairs ${n}: ${shown} has ${length} entries")
    endif()
    foreach(i RANGE ${last})
      string(JSON value GET "${json_${n}}" ${keys} ${i})
      if(value MATCHES "^-" OR value MATCHES "^0(\\.0*)?$")
        message(FATAL_ERROR "--flicker-pairs ${n}: ${shown} ${i} is ${value}, not positive")
      endif()
    endforeach()
    string(JSON last_${n}_${key} GET "${json_${n}}" ${keys} ${last})
  endforeach()
  string(JSON first_frame GET "${json_${n}}" flicker pair_first_frames 0)
  math(EXPR expected "${FRAMES} - 1 - ${n}")
  if(NOT first_frame EQUAL expected)
    message(FATAL_ERROR "--flicker-pairs ${n}: the first pair starts at frame ${first_frame}, not ${expected}")
  endif()
endforeach()
foreach(path IN LISTS lists)
  string(REPLACE "|" " " shown "${path}")
  string(REPLACE "|" "_" key "${path}")
  message(STATUS "${shown}: last of 3 ${last_3_${key}}, alone ${last_1_${key}}")
  if(NOT last_3_${key} STREQUAL last_1_${key})
    message(FATAL_ERROR "${shown}: the last pair reads ${last_3_${key}} among three and ${last_1_${key}} alone")
  endif()
endforeach()
