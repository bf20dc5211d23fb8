# The user guide's deck reference matches the code's own key lists.
impact3d_regress(docs/user_guide_keys "regression"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${CMAKE_SOURCE_DIR}/docs/user-guide.md)
