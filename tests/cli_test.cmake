# Runs the `mimic` command as a user would and checks its output and exit codes.
# cmake -DMIMIC=path/to/mimic -DSRC=source-dir -DOUT=scratch-dir -P cli_test.cmake
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})

function(run_ok)
  execute_process(COMMAND ${MIMIC} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "mimic ${ARGN} failed (${rc}):\n${out}\n${err}")
  endif()
  set(LAST_OUT "${out}${err}" PARENT_SCOPE)
endfunction()

function(run_fails expect)
  execute_process(COMMAND ${MIMIC} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "mimic ${ARGN} succeeded but should have failed")
  endif()
  string(FIND "${out}${err}" "${expect}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "mimic ${ARGN}: expected '${expect}' in:\n${out}${err}")
  endif()
endfunction()

function(expect_in text what)
  string(FIND "${text}" "${what}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "expected '${what}' in:\n${text}")
  endif()
endfunction()

# The README's main job on its embedded default.
run_ok(demo -o ${OUT}/demo --no-video)
expect_in("${LAST_OUT}" "jumping_jack")
foreach(f jumping_jack.mclip jumping_jack.svg summary.txt)
  if(NOT EXISTS ${OUT}/demo/${f})
    message(FATAL_ERROR "demo did not write ${f}")
  endif()
endforeach()

# Converting the built-in clip back and forth.
run_ok(motion info ${OUT}/demo/jumping_jack.mclip)
expect_in("${LAST_OUT}" "28 at 30.000 Hz")
run_ok(motion convert ${OUT}/demo/jumping_jack.mclip -o ${OUT}/jj60.mclip --fps 60)
run_ok(motion info ${OUT}/jj60.mclip)
expect_in("${LAST_OUT}" "55 at 60.000 Hz")
run_ok(motion mirror ${OUT}/demo/jumping_jack.mclip -o ${OUT}/jj_mirror.mclip)

# Models a user can open in any MuJoCo viewer.
run_ok(character build --builtin walker -o ${OUT}/walker.xml)
run_ok(character build ${OUT}/demo/jumping_jack.mclip --mass 60 -o ${OUT}/jack_body.xml)
expect_in("${LAST_OUT}" "60.00 kg")
run_fails("give a source file or --builtin" character build -o ${OUT}/nothing.xml)

# Bad input: a clear error naming the file, non-zero exit, no crash.
file(WRITE ${OUT}/broken.bvh "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n}\nMOTION\nFrames: 2\nFrame Time: 0.03\n1 2 3 4 5 6\n1 2 3\n")
run_fails("broken.bvh:11: frame 1 has 3 values, expected 6" motion info ${OUT}/broken.bvh)
run_fails("unknown output format" motion convert ${OUT}/demo/jumping_jack.mclip -o ${OUT}/x.xyz)
file(WRITE ${OUT}/walk.txt "{\"Loop\": \"wrap\", \"Frames\": []}")
run_fails("needs its character file (--character FILE)" motion info ${OUT}/walk.txt)
run_fails("does not exist" motion info ${OUT}/missing.bvh)

# With the shared data: the DeepMimic walk and the CMU retarget.
set(DATA ${SRC}/../shared/data)
if(DEFINED ENV{MIMIC_DATA})
  set(DATA $ENV{MIMIC_DATA})
endif()
if(EXISTS ${DATA}/deepmimic/motions/humanoid3d_walk.txt)
  run_ok(motion info ${DATA}/deepmimic/motions/humanoid3d_walk.txt)
  expect_in("${LAST_OUT}" "39 at 30.001 Hz = 1.267 s, loop wrap")
  run_ok(motion retarget ${DATA}/cmu-bvh/131_01.bvh --scale 0.056444 --map ${SRC}/data/retarget/cmu_to_humanoid3d.yaml
         --target ${DATA}/deepmimic/characters/humanoid3d.txt -o ${OUT}/cmu_walk.txt)
  expect_in("${LAST_OUT}" "end-effector error")
  run_ok(motion info ${OUT}/cmu_walk.txt --character ${DATA}/deepmimic/characters/humanoid3d.txt)
  expect_in("${LAST_OUT}" "994 at 120.000 Hz")
  run_ok(character build ${DATA}/deepmimic/characters/humanoid3d.txt --ctrl ${DATA}/deepmimic/characters/humanoid3d_ctrl.txt -o ${OUT}/humanoid3d.xml)
  expect_in("${LAST_OUT}" "15 bodies, 45.00 kg, 1.619 m tall at rest")
  run_fails("does not fit the character" render ${DATA}/cmu-bvh/131_01.bvh --character ${DATA}/deepmimic/characters/humanoid3d.txt -o ${OUT}/x.mp4)
else()
  message(STATUS "shared data not found: skipped the DeepMimic/CMU part")
endif()
