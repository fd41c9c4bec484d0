# The fuzz targets' seed corpora, made from the repository's own files at build time (nothing
# downloaded):
#   OUT/model/  examples/*.json and the model of each study in studies/
#   OUT/study/  studies/*.json; each example embedded in a small study (a range, variants, a
#               record), and each example named by a study's "model_file"
#
#     cmake -DSOURCE_DIR=<repository> -DOUT=<directory> -P fuzz/make_corpus.cmake
cmake_minimum_required(VERSION 3.20)

file(REMOVE_RECURSE "${OUT}/model" "${OUT}/study")
file(MAKE_DIRECTORY "${OUT}/model" "${OUT}/study")
file(GLOB examples "${SOURCE_DIR}/examples/*.json")
file(GLOB studies "${SOURCE_DIR}/studies/*.json")

foreach(example IN LISTS examples)
  get_filename_component(name "${example}" NAME_WE)
  file(READ "${example}" model)
  file(COPY "${example}" DESTINATION "${OUT}/model")
  set(sweep "[{\"name\": \"divisions\", \"path\": \"/members/0/divisions\", \"range\": [1, 3]},
  {\"name\": \"variant\", \"variants\": [{\"label\": \"as is\", \"set\": {\"/title\": \"${name}\"}},
   {\"label\": \"a load more\", \"set\": {\"/loads/-\": {\"node\": 1, \"fx\": 1.0}}}]}]")
  set(record "[{\"name\": \"peak\", \"quantity\": \"load_factor\", \"of\": \"max\"},
  {\"name\": \"tip\", \"quantity\": \"displacement\", \"node\": 1, \"dof\": \"uy\", \"of\": \"max_abs\"}]")
  file(WRITE "${OUT}/study/${name}-embedded.json"
       "{\"format\": \"tsmframe-study/1\", \"title\": \"${name}\",\n \"model\": ${model},\n \"sweep\": ${sweep},\n \"record\": ${record}}\n")
  file(WRITE "${OUT}/study/${name}-file.json"
       "{\"format\": \"tsmframe-study/1\", \"model_file\": \"${name}.json\",\n \"sweep\": [{\"name\": \"steps\", \"path\": \"/analysis/control/steps\", \"values\": [1, 2]}]}\n")
endforeach()

foreach(study IN LISTS studies)
  get_filename_component(name "${study}" NAME_WE)
  file(COPY "${study}" DESTINATION "${OUT}/study")
  file(READ "${study}" text)
  string(JSON model ERROR_VARIABLE no_model GET "${text}" model)
  if(NOT no_model)
    file(WRITE "${OUT}/model/study-${name}.json" "${model}\n")
  endif()
endforeach()
