# tools/plot_history.py on history.txt and a probe CSV: PNGs written; an
# unknown column is refused naming file, column, suggestion.
impact3d_regress(tools/plot_history "regression"
  ${PYTHON3} ${CMAKE_CURRENT_LIST_DIR}/check.py ${EXE} ${WORK}/plot_history)
