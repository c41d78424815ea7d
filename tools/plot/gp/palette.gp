
# line colours, one per file or mode (matplotlib's tab10)
array palette[8] = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf']
