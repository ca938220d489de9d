# run_trade(COMMAND OUT JSON_VAR): runs a `lantern trade ...` command line with `--out OUT` (OUT
# removed first), fails the test with its exit code and stderr unless it succeeds, and reads
# OUT/trade.json into JSON_VAR. Included by the trade_*.cmake test scripts.
function(run_trade command out json_var)
  file(REMOVE_RECURSE ${out})
  separate_arguments(cmd UNIX_COMMAND "${command} --out ${out}")
  execute_process(COMMAND ${cmd} RESULT_VARIABLE code ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "`${command}` failed (${code}): ${err}")
  endif()
  file(READ ${out}/trade.json json)
  set(${json_var} "${json}" PARENT_SCOPE)
endfunction()
