# `lantern trade --render-scale 0.5` against the same run at scale 1: the denoised frames are
# rendered at half the size and upscaled back (trade.json names the internal size; their relMSE
# is taken against the full-size reference, so a frame left at the internal size would fail the
# run), and they differ from the full-size ones; the raw columns stay at full size, so their
# relMSE is the same in both runs.
include(${CMAKE_CURRENT_LIST_DIR}/trade_run.cmake)
foreach(scale 1 0.5)
  run_trade("${COMMAND} --render-scale ${scale}" ${WORK}_${scale} json_${scale})
  string(JSON raw_${scale} GET "${json_${scale}}" rows 0 relmse)
  string(JSON denoised_${scale} GET "${json_${scale}}" rows 0 relmse_denoised)
  string(JSON internal_w_${scale} GET "${json_${scale}}" denoised_internal_size 0)
  string(JSON internal_h_${scale} GET "${json_${scale}}" denoised_internal_size 1)
  message(STATUS "scale ${scale}: internal ${internal_w_${scale}}x${internal_h_${scale}}, raw ${raw_${scale}}, denoised ${denoised_${scale}}")
endforeach()
if(NOT "${internal_w_1}x${internal_h_1}" STREQUAL "${WIDTH}x${HEIGHT}")
  message(FATAL_ERROR "scale 1 rendered at ${internal_w_1}x${internal_h_1}, not ${WIDTH}x${HEIGHT}")
endif()
if(NOT "${internal_w_0.5}x${internal_h_0.5}" STREQUAL "${HALF_WIDTH}x${HALF_HEIGHT}")
  message(FATAL_ERROR "scale 0.5 rendered at ${internal_w_0.5}x${internal_h_0.5}, not ${HALF_WIDTH}x${HALF_HEIGHT}")
endif()
if(NOT raw_1 STREQUAL raw_0.5)
  message(FATAL_ERROR "raw relMSE differs (${raw_1} vs ${raw_0.5}): the raw columns must stay at full size")
endif()
if(denoised_1 STREQUAL denoised_0.5)
  message(FATAL_ERROR "denoised relMSE is the same at both scales (${denoised_1}): the scale did not reach the denoised frames")
endif()
