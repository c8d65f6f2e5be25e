# `mimic video synth`, `mimic video keypoints`, `mimic reconstruct`, `mimic table` of
# reconstructions and `mimic complete`, run as a user would on DeepMimic's walk: the benchmark with a known answer, the
# pose model on a rendered video of it, the reconstruction to a skill, and bad input named.
# cmake -DMIMIC=path/to/mimic -DSRC=source-dir -DOUT=scratch-dir [-DSANITIZED=ON] -P video_cli_test.cmake
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})

include(${CMAKE_CURRENT_LIST_DIR}/cli_helpers.cmake)

set(DATA ${SRC}/../shared/data)
if(DEFINED ENV{MIMIC_DATA})
  set(DATA $ENV{MIMIC_DATA})
endif()
set(walk ${DATA}/deepmimic/motions/humanoid3d_walk.txt)
set(character ${DATA}/deepmimic/characters/humanoid3d.txt)
if(NOT EXISTS ${walk} OR NOT EXISTS ${character})
  message(STATUS "skipped: the video commands are checked on DeepMimic's walk and humanoid, absent from ${DATA}")
  return()
endif()

# Keypoints a known camera sees of the walk, reconstructed and measured against it.
run_ok(video synth ${walk} -o ${OUT}/walk_synth.json --seed 3)
expect_in("${LAST_OUT}" "38 frames of 15 keypoints at 30 fps")
run_ok(reconstruct ${OUT}/walk_synth.json --character ${character} -o ${OUT}/walk_rec.mclip --raw ${OUT}/walk_raw.mclip --truth ${walk}
       --json ${OUT}/walk_rec.json)
expect_in("${LAST_OUT}" "frames: 38 reconstructed from track frame 0; 0 could not be fitted")
expect_in("${LAST_OUT}" "MPJPE (m)")
foreach(f walk_rec.mclip walk_raw.mclip walk_rec.json)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "reconstruct did not write ${f}")
  endif()
endforeach()
file(READ ${OUT}/walk_rec.json report)
foreach(key "\"mpjpe_m\": {\"raw\": " "\"pa_mpjpe_m\"" "\"jitter\"" "\"terms\"" "\"unfit\": []")
  expect_in("${report}" "${key}")
endforeach()
run_ok(motion info ${OUT}/walk_rec.mclip)
expect_in("${LAST_OUT}" "38 at 30.000 Hz")
# Played on the character it was reconstructed on (found by its skeleton), not a simple body.
run_ok(render ${OUT}/walk_rec.mclip -o ${OUT}/walk_rec.mp4 --seconds 0.2 --width 160 --height 120)
expect_in("${LAST_OUT}" "character 'humanoid3d'")
# A camera that stays put (a pose model then sees the travel); a policy's video refuses it.
run_ok(render ${OUT}/walk_rec.mclip -o ${OUT}/walk_rec_fixed.mp4 --seconds 0.2 --width 160 --height 120 --fixed-camera)
run_fails("--fixed-camera is for a clip" render ${OUT} -o ${OUT}/x.mp4 --fixed-camera)
run_ok(table ${OUT}/walk_rec.json --names walk -o ${OUT}/table.md)
expect_in("${LAST_OUT}" "| walk | 38 |")
run_fails_named("walk_synth.json:1: the evaluation: missing \"run\"" table ${OUT}/walk_synth.json)

# Motion completion from one frame of those keypoints: the walk, near the frame, carried on.
set(skills ${SRC}/models/humanoid_walk_iccgan ${SRC}/models/humanoid_run_iccgan_straight_loop)
run_ok(complete ${OUT}/walk_synth.json --frame 12 --skills ${skills} --seconds 1 --json ${OUT}/complete.json)
expect_in("${LAST_OUT}" "completing with humanoid_walk_iccgan, from the frame")
expect_in("${LAST_OUT}" "simulated 1.0 s: the character stayed up")
file(READ ${OUT}/complete.json completion)
foreach(key "\"skill\": \"humanoid_walk_iccgan\"" "\"clip\": \"humanoid3d_walk\"" "\"fell\": false")
  expect_in("${completion}" "${key}")
endforeach()
run_fails_named("walk_synth.json: no frame 99 (it has 38, from 0)" complete ${OUT}/walk_synth.json --frame 99 --skills ${skills})
run_fails_named("skill 'walker_ppo' (" complete ${OUT}/walk_synth.json --skills ${SRC}/models/walker_ppo)

# A real pose model on a rendered video of the walk, the reconstruction from its keypoints and a
# skill from that (the end-to-end path; skipped where scripts/setup.sh has not installed the pose
# estimator).
if(NOT EXISTS ${SRC}/tools/pose/node_modules/@tensorflow/tfjs-backend-wasm OR NOT EXISTS ${SRC}/tools/pose/models/blazepose-full.bin)
  message(STATUS "skipped the pose model checks: tools/pose is not installed (scripts/setup.sh installs it)")
else()
  run_ok(render ${walk} -o ${OUT}/walk.mp4 --width 480 --height 360)
  run_ok(video keypoints ${OUT}/walk.mp4 -o ${OUT}/walk_video.json)
  expect_in("${LAST_OUT}" "a person in 39 of 39 frames (480x360 pixels at 30 fps)")
  run_ok(reconstruct ${OUT}/walk_video.json --character ${character} -o ${OUT}/walk_from_video.mclip --truth ${walk}
         --json ${OUT}/walk_video_rec.json)
  expect_in("${LAST_OUT}" "frames: 39 reconstructed")
  expect_in("${LAST_OUT}" "keypoints not on the character (unused): nose, left_eye_inner")
  # The reconstructed clip to a skill, at one small iteration (the pipeline, not the learning; in
  # the release build only: cli.commands runs `mimic imitate` under the sanitizers).
  if(NOT SANITIZED)
    run_ok(imitate ${OUT}/walk_from_video.mclip -o ${OUT}/imitate_video --samples 1 --trials 1 --video-seconds 0.5 --threads 1
           --set collect.samples=256 --set collect.envs=2 --set env.max_seconds=2)
    expect_in("${LAST_OUT}" "iter     1/1  samples        256 (100.0 %)")
    foreach(f model/networks.mimic model/clips/walk_from_video.mclip eval.json video.mp4 report.md)
      if(NOT EXISTS ${OUT}/imitate_video/${f})
        message(FATAL_ERROR "mimic imitate on the reconstructed clip wrote no ${f}")
      endif()
    endforeach()
  endif()
  # Motion completion from a still of the video: the walk, filmed.
  execute_process(COMMAND ffmpeg -v error -y -i ${OUT}/walk.mp4 -vf "select=eq(n\\,10)" -frames:v 1 ${OUT}/walk10.png RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "ffmpeg could not take a frame of the rendered walk")
  endif()
  run_ok(complete ${OUT}/walk10.png --skills ${skills} --seconds 1 -o ${OUT}/completion.mp4)
  expect_in("${LAST_OUT}" "completing with humanoid_walk_iccgan")
  if(NOT EXISTS ${OUT}/completion.mp4)
    message(FATAL_ERROR "complete -o wrote no video")
  endif()
  run_fails_named("--frame picks a frame of a keypoint file; an image has one" complete ${OUT}/walk10.png --frame 2 --skills ${skills})
  run_fails_named("not a video ffmpeg can read" complete ${OUT}/walk_rec.mclip --skills ${skills})
  run_fails_named("not a video ffmpeg can read" video keypoints ${OUT}/walk_rec.mclip -o ${OUT}/x.json)
  # A video without a person.
  execute_process(COMMAND ffmpeg -v error -y -f lavfi -i color=c=gray:s=320x240:d=1:r=10 ${OUT}/gray.mp4 RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "ffmpeg could not make a grey video")
  endif()
  run_fails_named("no person found in any of its 10 frames" video keypoints ${OUT}/gray.mp4 -o ${OUT}/x.json)
endif()

# Bad input: named, exit 1.
file(WRITE ${OUT}/flat.json "[{\"image_id\": 1, \"keypoints\": [1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1]}]")
run_fails_named("the image size is unknown" reconstruct ${OUT}/flat.json --character ${character} -o ${OUT}/x.mclip)
run_fails_named("no frame has 3D keypoints" reconstruct ${OUT}/flat.json --character ${character} -o ${OUT}/x.mclip --image-size 640x480)
run_fails_named("--image-size 640by480: expected WIDTHxHEIGHT" reconstruct ${OUT}/flat.json --character ${character} -o ${OUT}/x.mclip --image-size 640by480)
file(WRITE ${OUT}/notkp.json "{\"hello\": 1}")
run_fails_named("not a keypoint file mimic reads" reconstruct ${OUT}/notkp.json --character ${character} -o ${OUT}/x.mclip)
