$ Nastran file written by meshio v5.0.0
BEGIN BULK
GRID*   1                                          0.E+0           0.E+0
*                  0.E+0
GRID*   2                                          1.E+0           0.E+0
*                  0.E+0
GRID*   3                                          2.E+0           0.E+0
*                  0.E+0
GRID*   4                                          0.E+0           1.E+0
*                  0.E+0
GRID*   5                                          1.E+0           1.E+0
*                  0.E+0
GRID*   6                                          2.E+0           1.E+0
*                  0.E+0
GRID*   7                                          0.E+0           0.E+0
*                  1.E+0
GRID*   8                                          1.E+0           0.E+0
*                  1.E+0
GRID*   9                                          2.E+0           0.E+0
*                  1.E+0
GRID*   10                                         0.E+0           1.E+0
*                  1.E+0
GRID*   11                                         1.E+0           1.E+0
*                  1.E+0
GRID*   12                                         2.E+0           1.E+0
*                  1.E+0
GRID*   13                                         0.E+0           5.E-1
*                  0.E+0
GRID*   14                                         0.E+0           1.E+0
*                  5.E-1
GRID*   15                                         0.E+0           5.E-1
*                  1.E+0
GRID*   16                                         0.E+0           0.E+0
*                  5.E-1
GRID*   17                                         1.E+0           5.E-1
*                  0.E+0
GRID*   18                                         1.E+0           1.E+0
*                  5.E-1
GRID*   19                                         1.E+0           5.E-1
*                  1.E+0
GRID*   20                                         1.E+0           0.E+0
*                  5.E-1
GRID*   21                                         2.E+0           5.E-1
*                  0.E+0
GRID*   22                                         2.E+0           1.E+0
*                  5.E-1
GRID*   23                                         2.E+0           5.E-1
*                  1.E+0
GRID*   24                                         2.E+0           0.E+0
*                  5.E-1
GRID*   25                                         5.E-1           0.E+0
*                  0.E+0
GRID*   26                                         5.E-1           0.E+0
*                  1.E+0
GRID*   27                                         5.E-1           1.E+0
*                  0.E+0
GRID*   28                                         5.E-1           1.E+0
*                  1.E+0
GRID*   29                                        1.5E+0           0.E+0
*                  0.E+0
GRID*   30                                        1.5E+0           0.E+0
*                  1.E+0
GRID*   31                                        1.5E+0           1.E+0
*                  0.E+0
GRID*   32                                        1.5E+0           1.E+0
*                  1.E+0
GRID*   33                                         0.E+0          2.5E-1
*                  0.E+0
GRID*   34                                         0.E+0          7.5E-1
*                  0.E+0
GRID*   35                                         0.E+0           1.E+0
*                 7.5E-1
GRID*   36                                         0.E+0          2.5E-1
*                  1.E+0
GRID*   37                                         0.E+0           0.E+0
*                 2.5E-1
GRID*   38                                         1.E+0          7.5E-1
*                  0.E+0
GRID*   39                                         1.E+0           1.E+0
*                 7.5E-1
GRID*   40                                         1.E+0          2.5E-1
*                  1.E+0
GRID*   41                                         1.E+0           0.E+0
*                 2.5E-1
GRID*   42                                         2.E+0          7.5E-1
*                  0.E+0
GRID*   43                                         2.E+0           1.E+0
*                 7.5E-1
GRID*   44                                         2.E+0          2.5E-1
*                  1.E+0
GRID*   45                                         2.E+0           0.E+0
*                 2.5E-1
GRID*   46                                        7.5E-1           0.E+0
*                  0.E+0
GRID*   47                                        2.5E-1           0.E+0
*                  1.E+0
GRID*   48                                        7.5E-1           1.E+0
*                  0.E+0
GRID*   49                                        2.5E-1           1.E+0
*                  1.E+0
GRID*   50                                       1.75E+0           0.E+0
*                  0.E+0
GRID*   51                                       1.25E+0           0.E+0
*                  1.E+0
GRID*   52                                       1.75E+0           1.E+0
*                  0.E+0
GRID*   53                                       1.25E+0           1.E+0
*                  1.E+0
GRID*   54                                         0.E+0           1.E+0
*                 2.5E-1
GRID*   55                                         0.E+0          7.5E-1
*                  1.E+0
GRID*   56                                         0.E+0           0.E+0
*                 7.5E-1
GRID*   57                                         1.E+0          2.5E-1
*                  0.E+0
GRID*   58                                         1.E+0           1.E+0
*                 2.5E-1
GRID*   59                                         1.E+0          7.5E-1
*                  1.E+0
GRID*   60                                         1.E+0           0.E+0
*                 7.5E-1
GRID*   61                                         2.E+0          2.5E-1
*                  0.E+0
GRID*   62                                         2.E+0           1.E+0
*                 2.5E-1
GRID*   63                                         2.E+0          7.5E-1
*                  1.E+0
GRID*   64                                         2.E+0           0.E+0
*                 7.5E-1
GRID*   65                                        2.5E-1           0.E+0
*                  0.E+0
GRID*   66                                        7.5E-1           0.E+0
*                  1.E+0
GRID*   67                                        2.5E-1           1.E+0
*                  0.E+0
GRID*   68                                        7.5E-1           1.E+0
*                  1.E+0
GRID*   69                                       1.25E+0           0.E+0
*                  0.E+0
GRID*   70                                       1.75E+0           0.E+0
*                  1.E+0
GRID*   71                                       1.25E+0           1.E+0
*                  0.E+0
GRID*   72                                       1.75E+0           1.E+0
*                  1.E+0
GRID*   73                                        1.5E+0           0.E+0
*                  5.E-1
GRID*   74                                         0.E+0           5.E-1
*                  5.E-1
GRID*   75                                         5.E-1           0.E+0
*                  5.E-1
GRID*   76                                         5.E-1           1.E+0
*                  5.E-1
GRID*   77                                         5.E-1           5.E-1
*                  1.E+0
GRID*   78                                        1.5E+0           1.E+0
*                  5.E-1
GRID*   79                                        1.5E+0           5.E-1
*                  1.E+0
GRID*   80                                         1.E+0           5.E-1
*                  5.E-1
GRID*   81                                         2.E+0           5.E-1
*                  5.E-1
GRID*   82                                         5.E-1           5.E-1
*                  0.E+0
GRID*   83                                        1.5E+0           5.E-1
*                  0.E+0
CTETRA  1               32      53      78      79      
CTETRA  2               50      45      61      83      
CTETRA  3               39      68      76      77      
CTETRA  4               52      42      62      78      
CTETRA  5               35      49      55      77      
CTETRA  6               41      20      73      80      
CTETRA  7               7       36      47      56      
CTETRA  8               33      37      65      75      
CTETRA  9               44      64      73      81      
CTETRA  10              78      43      79      81      
CTETRA  11              44      73      79      81      
CTETRA  12              74      76      77      80      
CTETRA  13              11      39      59      68      
CTETRA  14              58      38      78      80      
CTETRA  15              33      74      75      82      
CTETRA  16              73      78      81      83      
CTETRA  17              71      31      78      83      
CTETRA  18              41      46      75      82      
CTETRA  19              57      41      69      83      
CTETRA  20              41      57      80      83      
CTETRA  21              34      67      76      82      
CTETRA  22              19      59      79      80      
CTETRA  23              64      24      73      81      
CTETRA  24              40      60      66      75      
CTETRA  25              35      74      76      77      
CTETRA  26              26      66      75      77      
CTETRA  27              52      42      78      83      
CTETRA  28              33      13      74      82      
CTETRA  29              40      19      79      80      
CTETRA  30              49      35      76      77      
CTETRA  31              30      70      73      79      
CTETRA  32              60      20      75      80      
CTETRA  33              55      15      74      77      
CTETRA  34              54      34      67      76      
CTETRA  35              42      21      81      83      
CTETRA  36              16      37      74      75      
CTETRA  37              19      40      77      80      
CTETRA  38              73      41      80      83      
CTETRA  39              10      35      49      55      
CTETRA  40              36      47      56      75      
CTETRA  41              20      60      73      80      
CTETRA  42              8       40      60      66      
CTETRA  43              11      39      53      59      
CTETRA  44              56      16      74      75      
CTETRA  45              39      78      79      80      
CTETRA  46              57      17      80      83      
CTETRA  47              47      26      75      77      
CTETRA  48              74      34      76      82      
CTETRA  49              45      50      73      83      
CTETRA  50              42      6       52      62      
CTETRA  51              78      42      81      83      
CTETRA  52              38      78      80      83      
CTETRA  53              41      2       57      69      
CTETRA  54              40      51      73      79      
CTETRA  55              66      40      75      77      
CTETRA  56              45      3       50      61      
CTETRA  57              38      5       58      71      
CTETRA  58              58      38      71      78      
CTETRA  59              76      39      77      80      
CTETRA  60              40      60      75      80      
CTETRA  61              45      73      81      83      
CTETRA  62              28      49      76      77      
CTETRA  63              39      53      59      79      
CTETRA  64              38      58      76      80      
CTETRA  65              54      14      74      76      
CTETRA  66              68      28      76      77      
CTETRA  67              73      40      79      80      
CTETRA  68              73      78      79      81      
CTETRA  69              24      45      73      81      
CTETRA  70              41      2       46      57      
CTETRA  71              38      5       48      58      
CTETRA  72              40      75      77      80      
CTETRA  73              43      63      72      79      
CTETRA  74              14      35      74      76      
CTETRA  75              8       40      51      60      
CTETRA  76              48      38      76      82      
CTETRA  77              39      59      77      80      
CTETRA  78              15      36      74      77      
CTETRA  79              46      25      75      82      
CTETRA  80              1       33      37      65      
CTETRA  81              25      65      75      82      
CTETRA  82              78      73      80      83      
CTETRA  83              48      38      58      76      
CTETRA  84              34      4       54      67      
CTETRA  85              23      44      79      81      
CTETRA  86              17      38      80      83      
CTETRA  87              74      36      75      77      
CTETRA  88              36      47      75      77      
CTETRA  89              9       44      64      70      
CTETRA  90              39      59      68      77      
CTETRA  91              75      74      77      80      
CTETRA  92              12      43      63      72      
CTETRA  93              70      44      73      79      
CTETRA  94              63      23      79      81      
CTETRA  95              43      63      79      81      
CTETRA  96              75      74      80      82      
CTETRA  97              40      51      60      73      
CTETRA  98              42      62      78      81      
CTETRA  99              44      64      70      73      
CTETRA  100             22      43      78      81      
CTETRA  101             51      30      73      79      
CTETRA  102             72      32      78      79      
CTETRA  103             29      69      73      83      
CTETRA  104             50      29      73      83      
CTETRA  105             20      41      75      80      
CTETRA  106             27      48      76      82      
CTETRA  107             74      76      80      82      
CTETRA  108             57      41      80      82      
CTETRA  109             31      52      78      83      
CTETRA  110             46      41      57      82      
CTETRA  111             62      22      78      81      
CTETRA  112             13      34      74      82      
CTETRA  113             17      57      80      82      
CTETRA  114             41      75      80      82      
CTETRA  115             67      27      76      82      
CTETRA  116             37      33      74      75      
CTETRA  117             36      56      74      75      
CTETRA  118             34      54      74      76      
CTETRA  119             38      71      78      83      
CTETRA  120             35      55      74      77      
CTETRA  121             60      40      73      80      
CTETRA  122             59      39      79      80      
CTETRA  123             78      73      79      80      
CTETRA  124             38      17      80      82      
CTETRA  125             43      72      78      79      
CTETRA  126             53      39      78      79      
CTETRA  127             76      38      80      82      
CTETRA  128             65      33      75      82      
CTETRA  129             59      19      77      80      
CTETRA  130             18      58      78      80      
CTETRA  131             39      18      78      80      
CTETRA  132             58      18      76      80      
CTETRA  133             18      39      76      80      
CTETRA  134             21      61      81      83      
CTETRA  135             69      41      73      83      
CTETRA  136             61      45      81      83      
ENDDATA
