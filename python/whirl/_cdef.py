"""The C declarations of libwhirl that the package calls (cffi ABI mode). The build parses them
into the module whirl/_ffi.py (whirl/_build.py), which the installed package imports; a source
tree parses them at its first import and keeps that module in its build/python/ (whirl._lib).

They mirror include/whirl/*.h; tests/test_layout.py compiles a C program against those headers
and checks that every struct declared here has the same size and field offsets."""

CDEF = r"""
#define WHIRL_MODE_MAX 64
#define WHIRL_SHAPE_NODES 64
#define WHIRL_CONTINUUM_MODE_MAX 3183
#define WHIRL_EINTERRUPTED 1000
#define WHIRL_DRIVEN_FOLD_MAX 32

typedef void gsl_error_handler_t(const char *reason, const char *file, int line, int gsl_errno);
gsl_error_handler_t *gsl_set_error_handler_off(void);

const char *whirl_last_error(void);
const char *whirl_version(void);
int whirl_last_status(void);
char *whirl_last_error_in_units(char *buf, size_t size, int physical, double length,
                                double mass, double gravity, int rate_hz);
void whirl_stop_request(void);
int whirl_stop_requested(void);
void whirl_stop_clear(void);
int whirl_stop_signal(void);
int whirl_stop_catch_signals(void);
void whirl_stop_restore_signals(void);
#define WHIRL_THREADS_MAX 4096
int whirl_set_max_threads(int threads);
int whirl_max_threads(void);
int whirl_forked_child(void);
typedef enum {
    WHIRL_QUANTITY_NUMBER,
    WHIRL_QUANTITY_RATE,
    WHIRL_QUANTITY_LENGTH,
    WHIRL_QUANTITY_MASS,
    WHIRL_QUANTITY_TIME
} whirl_quantity;
int whirl_parse_quantity(const char *text, whirl_quantity kind, double *value, int *suffixed);
const char *whirl_quantity_suffixes(whirl_quantity kind);

typedef struct whirl_chain {
    size_t n;
    double *length;
    double *mass;
    double gravity;
} whirl_chain;
whirl_chain *whirl_chain_alloc_uniform(size_t n, double tip_mass);
whirl_chain *whirl_chain_alloc(size_t n, const double *length, const double *mass, double g);
void whirl_chain_free(whirl_chain *c);
double whirl_chain_total_length(const whirl_chain *c);
double whirl_chain_total_mass(const whirl_chain *c);

typedef struct whirl_shape_info {
    double omega;
    int mode;
    double tip_r;
    double max_r;
    double top_tension;
    double depth;
    int n_nodes;
    double node_s[64];
} whirl_shape_info;
int whirl_continuum_critical(int mode, double tip_mass, double *omega);
int whirl_continuum_critical_rates(size_t n, double tip_mass, double *omega);
int whirl_continuum_solve(double omega, int mode, double tip_mass, double tip_r_guess,
                          whirl_shape_info *info);
int whirl_continuum_sample(double omega, double tip_mass, double tip_r, size_t npts, double *s,
                           double *r, double *z, double *tension);
int whirl_continuum_branch(int mode, double tip_mass, size_t n, const double *omega,
                           whirl_shape_info *info, int *exists);
int whirl_nlink_critical(const whirl_chain *c, size_t nmodes, double *omega);
typedef void (*whirl_nlink_critical_progress_fn)(void *ctx, size_t done, size_t total);
int whirl_nlink_critical_report(const whirl_chain *c, size_t nmodes, double *omega,
                                whirl_nlink_critical_progress_fn progress, void *ctx);
int whirl_nlink_solve(const whirl_chain *c, double omega, int mode, whirl_shape_info *info);
int whirl_nlink_positions(const whirl_chain *c, double omega, double tip_r, double *r, double *z,
                          double *tension);
size_t whirl_nlink_node_arclengths(const whirl_chain *c, double omega, const double *r,
                                   size_t max, double *node_s, size_t *resolved);
int whirl_nlink_branch(const whirl_chain *c, int mode, size_t n, const double *omega,
                       whirl_shape_info *info, int *exists);
int whirl_nlink_solve_nodes(const whirl_chain *c, double omega, int mode,
                            whirl_shape_info *info, double *r, double *z, double *tension);
int whirl_nlink_branch_nodes(const whirl_chain *c, int mode, size_t n, const double *omega,
                             whirl_shape_info *info, int *exists, double *r, double *z,
                             double *tension);

typedef enum { WHIRL_FRAME_INERTIAL = 0, WHIRL_FRAME_ROTATING = 1 } whirl_frame;
typedef enum { WHIRL_FORMULATION_CARTESIAN = 0, WHIRL_FORMULATION_SEED = 1 } whirl_formulation;
typedef struct whirl_ramp {
    double from;
    double to;
    double t_start;
    double t_end;
} whirl_ramp;
typedef struct whirl_model {
    const whirl_chain *chain;
    int dim;
    whirl_frame frame;
    double omega;
    double drive_radius;
    double air_drag;
    double air_drag_quadratic;
    double internal_damping;
    const double *seed_sigma;
    const double *seed_lambda;
    whirl_ramp drive_radius_ramp;
    whirl_ramp omega_ramp;
} whirl_model;
typedef struct whirl_dyn whirl_dyn;
whirl_dyn *whirl_dyn_alloc(const whirl_model *model, whirl_formulation f);
void whirl_dyn_free(whirl_dyn *d);
size_t whirl_dyn_size(const whirl_dyn *d);
int whirl_dyn_set_state(whirl_dyn *d, double t, const double *x, const double *v, double *y);
int whirl_dyn_get_state(const whirl_dyn *d, double t, const double *y, whirl_frame frame,
                        double *x, double *v);
int whirl_dyn_tensions(whirl_dyn *d, double t, const double *y, double *tension);
typedef struct whirl_dyn_diagnostics {
    double energy;
    double lz;
    double jacobi;
    double constraint;
} whirl_dyn_diagnostics;
int whirl_dyn_diagnose(const whirl_dyn *d, double t, const double *y, whirl_dyn_diagnostics *out);
double whirl_deviation(size_t n, const double *x, const double *ref);

typedef struct whirl_integrator whirl_integrator;
typedef struct whirl_integrator_stats {
    unsigned long steps;
    unsigned long rejected;
    unsigned long rhs_evals;
    unsigned long iterations;
} whirl_integrator_stats;
const char *const *whirl_integrator_methods(void);
whirl_integrator *whirl_integrator_alloc(const char *method, whirl_dyn *d);
void whirl_integrator_free(whirl_integrator *it);
int whirl_integrator_advance(whirl_integrator *it, double *t, double *y, double t1, double h,
                             double tol);
whirl_integrator_stats whirl_integrator_get_stats(const whirl_integrator *it);

typedef struct whirl_stability whirl_stability;
whirl_stability *whirl_stability_alloc(size_t n);
void whirl_stability_free(whirl_stability *w);
int whirl_stability_eigenvalues(whirl_stability *w, size_t *count, const double **re,
                                const double **im);
int whirl_stability_linearise(whirl_stability *w, const whirl_model *model, const double *r,
                              const double *z);
int whirl_stability_growth(whirl_stability *w, double *growth);
int whirl_stability_shape(whirl_stability *w, const whirl_model *model, double tip_r,
                          double *growth);
void whirl_stability_nodes(const whirl_stability *w, const double **x, const double **y,
                           const double **z);
typedef enum {
    WHIRL_VERDICT_STABLE = 0,
    WHIRL_VERDICT_UNSTABLE = 1,
    WHIRL_VERDICT_CONVERGING = 2,
    WHIRL_VERDICT_NEUTRAL = 3
} whirl_verdict;
const char *whirl_verdict_name(whirl_verdict v);
typedef struct whirl_stability_point {
    double omega;
    const double *r, *z;
    int skip;
    double growth;
    int status;
    int index;
} whirl_stability_point;
typedef void (*whirl_stability_map_progress)(void *ctx, size_t done);
int whirl_stability_map(const whirl_chain *c, double damping, size_t n,
                        whirl_stability_point *pts, whirl_stability_map_progress progress,
                        void *ctx);
whirl_verdict whirl_verdict_refine(whirl_verdict v, int index);
whirl_verdict whirl_verdict_linear(double growth, int index);
int whirl_stability_index(const whirl_stability *w, int *index);
void whirl_stability_set_tick(whirl_stability *w, void (*tick)(void *data), void *data);
typedef struct whirl_stability_modes {
    size_t links;
    size_t count;
    double *re, *im;
    double *angle_re, *angle_im;
    double *node_re, *node_im;
    int *krein;
} whirl_stability_modes;
whirl_stability_modes *whirl_stability_modes_alloc(size_t n);
void whirl_stability_modes_free(whirl_stability_modes *m);
int whirl_stability_eigenvectors(whirl_stability *w, whirl_stability_modes *out);
int whirl_perturb_links_along(size_t n, double *links, double eps, const double *along);
typedef struct whirl_stability_run_params {
    double periods;
    double perturbation;
    unsigned long seed;
    const char *method;
    double dt;
    int (*observe)(double t, double ratio, void *data);
    void *observe_data;
    const double *along;
} whirl_stability_run_params;
whirl_stability_run_params whirl_stability_run_defaults(void);
typedef struct whirl_stability_run_result {
    double sim_growth;
    double max_deviation;
    double end_deviation;
    double initial;
    double duration;
    double fit_from, fit_to;
    whirl_verdict verdict;
    whirl_integrator_stats stats;
} whirl_stability_run_result;
int whirl_stability_run_shape(const whirl_model *model, const double *x, const double *y,
                              const double *z, const whirl_stability_run_params *params,
                              whirl_stability_run_result *result);

typedef struct whirl_driven_params {
    double omega;
    double drive_radius;
    double air_drag;
    double air_drag_quadratic;
    double tip_mass;
} whirl_driven_params;
typedef struct whirl_driven_info {
    double omega;
    double tip[3];
    double tip_r;
    double top_force[3];
    double top_tension;
    double fold_function;
    int nodes;
    double residual;
    int iterations;
} whirl_driven_info;
int whirl_driven_mode(const whirl_chain *chain, const whirl_driven_params *params, int mode,
                      int side, whirl_driven_info *info);
int whirl_driven_sample(const whirl_chain *chain, const whirl_driven_params *params,
                        const double tip_xy[2], size_t npts, double *s, double *x, double *y,
                        double *z, double *tension);
int whirl_stability_driven_mode(whirl_stability *w, const whirl_model *model, int mode, int side,
                                whirl_driven_info *info, double *growth);

typedef struct whirl_fit_model {
    size_t links;
    double tip_mass;
    double omega_max;
    size_t samples;
} whirl_fit_model;
typedef struct whirl_fit_result {
    double omega;
    double omega_err;
    int mode;
    double rms_residual;
    int mirrored;
    int evaluations;
    int failures;
} whirl_fit_result;
whirl_fit_model whirl_fit_model_defaults(void);
int whirl_fit(const whirl_fit_model *m, size_t n, const double *r, const double *z, int mode,
              whirl_fit_result *result);

typedef enum {
    WHIRL_REGIME_SETTLED = 0,
    WHIRL_REGIME_PERIODIC = 1,
    WHIRL_REGIME_QUASIPERIODIC = 2,
    WHIRL_REGIME_CHAOTIC = 3,
    WHIRL_REGIME_FAILED = 4,
    WHIRL_REGIME_CONVERGING = 5
} whirl_regime_state;
typedef struct whirl_regime_params {
    double omega;
    double drive_radius;
    double air_drag;
    double air_drag_quadratic;
    double internal_damping;
    whirl_frame frame;
    const char *method;
    double dt;
    double t_ramp;
    double t_max;
    double settle_tol;
    int settle_periods;
    double periodic_tol;
    int lyapunov_periods;
    double chaos_lambda;
    double perturb;
    unsigned long seed;
} whirl_regime_params;
typedef struct whirl_regime_result {
    whirl_regime_state state;
    int nodes;
    int period;
    double t_end;
    double change;
    double remaining;
    double shape_error;
    int bvp_nodes;
    double lyapunov;
    double tip[3];
    double tip_r;
    unsigned long steps;
} whirl_regime_result;
typedef int (*whirl_regime_observer)(void *ctx, double t, double frame_angle, const double *pivot,
                                     const double *x, size_t n);
typedef struct whirl_regime whirl_regime;
whirl_regime *whirl_regime_alloc(const whirl_chain *chain);
void whirl_regime_free(whirl_regime *w);
void whirl_regime_observe(whirl_regime *w, whirl_regime_observer f, void *ctx, double every);
whirl_regime_params whirl_regime_defaults(size_t links);
int whirl_regime_run(whirl_regime *w, const whirl_regime_params *p, whirl_regime_result *res);
const char *whirl_regime_state_name(whirl_regime_state s);
"""

# The structs whose layout tests/test_layout.py checks against the C headers.
STRUCTS = ["whirl_chain", "whirl_shape_info", "whirl_ramp", "whirl_model", "whirl_dyn_diagnostics",
           "whirl_integrator_stats", "whirl_stability_run_params", "whirl_stability_run_result",
           "whirl_driven_params", "whirl_driven_info", "whirl_fit_model", "whirl_fit_result",
           "whirl_regime_params", "whirl_regime_result", "whirl_stability_point",
           "whirl_stability_modes"]

CDEF += r"""
int whirl_stability_mode(whirl_stability *w, const whirl_model *model, int mode,
                         whirl_shape_info *info, double *growth);
"""

CDEF += r"""
int whirl_regime_check(const whirl_regime_params *p);
"""

CDEF += r"""
int whirl_driven_solve(const whirl_chain *chain, const whirl_driven_params *params,
                       const double guess[2], whirl_driven_info *info);
"""

CDEF += r"""
typedef struct whirl_windows whirl_windows;
whirl_windows *whirl_windows_alloc(size_t n);
void whirl_windows_free(whirl_windows *w);
typedef struct whirl_windows_params {
    double omega_min, omega_max;
    double scan_step;
    double tol;
    int krylov;
} whirl_windows_params;
whirl_windows_params whirl_windows_defaults(void);
typedef struct whirl_window {
    double from, to;
    int open_from, open_to;
    double freq_from, freq_to;
    double max_growth;
    double at;
    double err_from, err_to;
} whirl_window;
typedef struct whirl_windows_stats {
    double omega_from, omega_to;
    size_t scan;
    size_t shapes;
    size_t solves_vectors;
    size_t solves_values;
    size_t solves_krylov;
    size_t approaches;
    size_t unresolved;
} whirl_windows_stats;
int whirl_windows_find(whirl_windows *w, const whirl_chain *c, int mode,
                       const whirl_windows_params *p, whirl_window *windows, size_t max,
                       size_t *count, whirl_windows_stats *stats);
"""
STRUCTS += ["whirl_windows_params", "whirl_window", "whirl_windows_stats"]

CDEF += r"""
typedef struct whirl_dissipative_interval {
    double from, to;
    int open_from, open_to;
    whirl_verdict verdict;
    double freq_from, freq_to;
    double growth;
    double at;
} whirl_dissipative_interval;
int whirl_windows_dissipative(const whirl_model *model, int mode, int side,
                              const whirl_windows_params *p,
                              whirl_dissipative_interval *out, size_t max,
                              size_t *count, whirl_windows_stats *stats);
"""
STRUCTS += ["whirl_dissipative_interval"]

CDEF += r"""
typedef struct whirl_equilibria_params {
    int stability;
    double follow_factor;
    long shot_budget;
    int continuation;
} whirl_equilibria_params;
whirl_equilibria_params whirl_equilibria_defaults(void);
typedef struct whirl_equilibrium {
    whirl_shape_info info;
    int branch;
    double born_at;
    double eig_growth;
    int index;
} whirl_equilibrium;
typedef struct whirl_equilibria {
    double omega;
    size_t n_links;
    size_t count;
    whirl_equilibrium *eq;
    int born;
    size_t tip_roots;
    double tip_floor;
    long tip_shots;
    int tip_levels;
    size_t tip_unresolved;
    size_t check_roots;
    long check_shots;
    int check_levels;
    size_t matched;
    size_t unpolished;
    size_t crossings;
    size_t missed;
    size_t isolated;
    size_t unidentified;
    long path_steps;
    size_t cut_short;
    double balance;
    size_t wrong_parity;
    size_t refined;
    size_t coincident;
} whirl_equilibria;
int whirl_equilibria_find(const whirl_chain *c, double tip_mass, double omega,
                          const whirl_equilibria_params *params, whirl_equilibria **out);
void whirl_equilibria_free(whirl_equilibria *e);
typedef struct whirl_equilibria_progress {
    int stage, stages;
    size_t done, total;
} whirl_equilibria_progress;
typedef void (*whirl_equilibria_progress_fn)(void *ctx, const whirl_equilibria_progress *at);
int whirl_equilibria_find_progress(const whirl_chain *c, double tip_mass, double omega,
                                   const whirl_equilibria_params *params,
                                   whirl_equilibria_progress_fn progress, void *ctx,
                                   whirl_equilibria **out);
"""
STRUCTS += ["whirl_equilibria_params", "whirl_equilibrium", "whirl_equilibria",
            "whirl_equilibria_progress"]

CDEF += r"""
typedef struct whirl_cstab whirl_cstab;
typedef struct whirl_cstab_params {
    int degree;
    double tip_mass;
    double shape_tol;
    double freq_max;
    int solver;
    double memory_mb;
    void (*progress)(void *ctx, int mode, double omega);
    void *progress_ctx;
} whirl_cstab_params;
whirl_cstab_params whirl_cstab_defaults(void);
whirl_cstab *whirl_cstab_alloc(const whirl_cstab_params *p);
void whirl_cstab_free(whirl_cstab *w);
int whirl_cstab_windows(whirl_cstab *w, int mode, const whirl_windows_params *p,
                        whirl_window *windows, size_t max, size_t *count,
                        whirl_windows_stats *stats);
"""
STRUCTS += ["whirl_cstab_params"]

CDEF += r"""
int whirl_shape_links(size_t n, const double *nx, const double *ny, const double *nz,
                      double *links);
int whirl_perturb_links(size_t n, double *links, double angle, unsigned long seed);
int whirl_dyn_state_from_shape(whirl_dyn *d, double t, const double *links, double spin,
                               double *y);
int whirl_dyn_set_threads(whirl_dyn *d, int threads);
"""

CDEF += r"""
#define WHIRL_SCENE_NKEYS 37
#define WHIRL_NCOLUMNS 9
typedef struct whirl_scene {
    char *path;
    int physical;
    int dim;
    size_t links;
    double *length;
    double *mass;
    double chain_length;
    double chain_mass;
    double gravity;
    int start;
    double start_omega;
    int mode;
    double perturb;
    unsigned long seed;
    double *theta;
    double *phi;
    double *theta_dot;
    double *phi_dot;
    whirl_frame frame;
    char *method;
    double dt;
    double t_end;
    whirl_formulation formulation;
    double omega;
    double drive_radius;
    double air_drag;
    double air_drag_quadratic;
    double internal_damping;
    double *seed_sigma;
    double *seed_lambda;
    double tol;
    double stop_deviation;
    int threads;
    double every;
    size_t n_columns;
    int columns[9];
    int want[9];
    char *trace;
    double trace_every;
    int reference_mode;
    int line[37];
} whirl_scene;
int whirl_scene_parse(const char *path, const char *const *overrides, size_t n_overrides,
                      whirl_scene *scene);
void whirl_scene_free(whirl_scene *scene);
const char *whirl_column_name(int c);
typedef struct whirl_scene_work whirl_scene_work;
typedef struct whirl_scene_output {
    int (*row)(void *ctx, const double *value);
    int (*frame)(void *ctx, double t, const double *pivot, const double *x, size_t n);
    int (*progress)(void *ctx, double t);
    void *ctx;
} whirl_scene_output;
typedef struct whirl_scene_result {
    double t;
    unsigned long rows, frames;
    int stopped;
    double deviation;
    whirl_integrator_stats stats;
} whirl_scene_result;
whirl_scene_work *whirl_scene_work_alloc(const whirl_scene *scene);
void whirl_scene_work_free(whirl_scene_work *w);
int whirl_scene_work_run(whirl_scene_work *w, const whirl_scene_output *out,
                         whirl_scene_result *res);
"""
STRUCTS += ["whirl_scene", "whirl_scene_output", "whirl_scene_result"]

# The constants whose values tests/test_layout.py checks against the C headers.
CONSTANTS = ["WHIRL_MODE_MAX", "WHIRL_SHAPE_NODES", "WHIRL_CONTINUUM_MODE_MAX",
             "WHIRL_EINTERRUPTED", "WHIRL_DRIVEN_FOLD_MAX", "WHIRL_SCENE_NKEYS",
             "WHIRL_NCOLUMNS", "WHIRL_THREADS_MAX"]

# The atlas (whirl.atlas), the hand-swung chain's branches (whirl.driven_branch).
CDEF += r"""
#define WHIRL_FORMAT_MAX 32
char *whirl_format_double(char *buf, double x);
typedef struct whirl_spectrum {
    size_t count;
    const double *re, *im;
    const int *signature;
    double growth;
    double level;
} whirl_spectrum;
int whirl_cstab_linearise(whirl_cstab *w, double omega, int mode, double tip_r_guess,
                          double *tip_r);
int whirl_cstab_spectrum(whirl_cstab *w, int signatures, whirl_spectrum *out);
int whirl_stability_linearise_3d(whirl_stability *w, const whirl_model *model,
                                 const double *x, const double *y, const double *z);
typedef struct whirl_driven_curve {
    size_t capacity;
    size_t n;
    whirl_driven_info *point;
    int *fold;
    size_t n_folds;
    double fold_omega[32];
    int complete;
} whirl_driven_curve;
whirl_driven_curve *whirl_driven_curve_alloc(size_t capacity);
void whirl_driven_curve_free(whirl_driven_curve *curve);
int whirl_driven_branch(const whirl_chain *chain, const whirl_driven_params *params,
                        const whirl_driven_info *start, int direction, double omega_min,
                        double omega_max, double step, whirl_driven_curve *curve);
typedef void (*whirl_driven_branch_tick_fn)(void *data, const whirl_driven_curve *curve);
int whirl_driven_branch_tick(const whirl_chain *chain, const whirl_driven_params *params,
                             const whirl_driven_info *start, int direction, double omega_min,
                             double omega_max, double step, whirl_driven_curve *curve,
                             whirl_driven_branch_tick_fn tick, void *data);
typedef void (*whirl_fit_progress_fn)(void *data, int mode, int first, int last, int evaluations);
int whirl_fit_observed(const whirl_fit_model *m, size_t n, const double *r, const double *z,
                       int mode, whirl_fit_progress_fn progress, void *data,
                       whirl_fit_result *result);
"""
STRUCTS += ["whirl_spectrum", "whirl_driven_curve"]

# The stability atlas (whirl/atlas.h; whirl.atlas).
CDEF += r"""
#define WHIRL_ATLAS_CHUNK 5
#define WHIRL_ATLAS_WINDOWS 4096
#define WHIRL_ATLAS_LINE_MAX 1024
typedef struct whirl_atlas_params {
    int modes[64];
    int n_modes;
    double omega_max;
    int degree;
    double tol;
    double scan_step;
    double memory_mb;
    void (*progress)(void *ctx, int mode, double omega);
    void *progress_ctx;
} whirl_atlas_params;
typedef struct whirl_atlas_row {
    int mode;
    whirl_window w;
    int sig_from, sig_to;
} whirl_atlas_row;
typedef struct whirl_atlas whirl_atlas;
whirl_atlas_params whirl_atlas_defaults(void);
whirl_atlas *whirl_atlas_alloc(const whirl_atlas_params *p);
void whirl_atlas_free(whirl_atlas *a);
size_t whirl_atlas_chunks(const whirl_atlas *a);
void whirl_atlas_chunk_range(const whirl_atlas *a, size_t j, double *lo, double *hi);
int whirl_atlas_done(const whirl_atlas *a, size_t k, size_t j);
size_t whirl_atlas_done_count(const whirl_atlas *a);
int whirl_atlas_compute(whirl_atlas *a, size_t k, size_t j, int *computed);
const whirl_atlas_row *whirl_atlas_rows(const whirl_atlas *a, size_t *count);
size_t whirl_atlas_row_text(const whirl_atlas_row *r, char *buf, size_t size);
size_t whirl_atlas_text(const whirl_atlas *a, char *buf, size_t size);
int whirl_atlas_read_text(whirl_atlas *a, const char *data, size_t size, const char *path);
typedef struct whirl_atlas_file whirl_atlas_file;
whirl_atlas_file *whirl_atlas_file_alloc(const char *path, int make);
int whirl_atlas_file_fd(const whirl_atlas_file *f);
int whirl_atlas_file_made(const whirl_atlas_file *f);
int whirl_atlas_file_replace(whirl_atlas_file *f, int fd, const char *tmp);
int whirl_atlas_file_commit(whirl_atlas_file *f, const char *data, size_t n);
void whirl_atlas_file_free(whirl_atlas_file *f);
"""
STRUCTS += ["whirl_atlas_params", "whirl_atlas_row"]
CONSTANTS += ["WHIRL_ATLAS_CHUNK", "WHIRL_ATLAS_WINDOWS", "WHIRL_ATLAS_LINE_MAX"]

# ---- periodic pivot paths, periodic motions, their Floquet multipliers (whirl/periodic.h) ----
CDEF += r"""
#define WHIRL_PIVOT_HARMONICS_MAX 8
typedef struct whirl_pivot_path {
    double omega;
    int harmonics;
    double c[3][8];
    double s[3][8];
} whirl_pivot_path;
int whirl_pivot_parse(const char *text, double omega, double length, int dim,
                      whirl_pivot_path *path);
int whirl_pivot_check(const whirl_pivot_path *path, int dim);
double whirl_pivot_period(const whirl_pivot_path *path);
int whirl_pivot_circle(whirl_pivot_path *path, double omega, double r);
void whirl_pivot_eval(double t, double p[3], double pv[3], double pa[3], void *path);
typedef void (*whirl_pivot_fn)(double t, double p[3], double pv[3], double pa[3], void *params);
int whirl_dyn_set_pivot(whirl_dyn *d, whirl_pivot_fn pivot, void *params);
typedef struct whirl_scene_pivot {
    int given;
    int line;
    whirl_pivot_path path;
} whirl_scene_pivot;
int whirl_scene_parse_with_pivot(const char *path, const char *const *overrides,
                                 size_t n_overrides, whirl_scene *scene,
                                 whirl_scene_pivot *pivot);
whirl_scene_work *whirl_scene_work_alloc_with_pivot(const whirl_scene *scene,
                                                    const whirl_scene_pivot *pivot);
typedef struct whirl_periodic whirl_periodic;
whirl_periodic *whirl_periodic_alloc(const whirl_chain *c, int dim, const whirl_pivot_path *path);
void whirl_periodic_free(whirl_periodic *w);
whirl_periodic *whirl_periodic_alloc_model(const whirl_model *model,
                                           const whirl_pivot_path *path);
int whirl_periodic_dissipative(const whirl_periodic *w);
whirl_dyn *whirl_periodic_dyn(whirl_periodic *w);
size_t whirl_periodic_state_size(const whirl_periodic *w);
size_t whirl_periodic_tangent_size(const whirl_periodic *w);
int whirl_periodic_start_vertical(whirl_periodic *w, int inverted, double *y);
typedef struct whirl_periodic_params {
    int steps;
    double tol;
    int max_iter;
    int refine;
    int monodromy;
} whirl_periodic_params;
typedef struct whirl_periodic_result {
    size_t count;
    double *re, *im;
    double *err;
    double residual;
    int iterations;
    int steps;
    double period;
    double max_modulus;
    double max_modulus_err;
    double reciprocal_err;
    double orbit_change;
    int verdict;
    double growth;
    double efold_periods;
    double efold_time;
    int edge;
    double edge_distance;
} whirl_periodic_result;
int whirl_periodic_find(whirl_periodic *w, double *y, const whirl_periodic_params *params,
                        whirl_periodic_result *result);
const double *whirl_periodic_monodromy(const whirl_periodic *w);
typedef struct whirl_chart_params {
    int inverted;
    double omega_min, omega_max;
    int columns;
    double amp_min;
    double amp_max;
    int rows;
    int steps;
    double tol;
} whirl_chart_params;
typedef struct whirl_chart_point {
    int kind;
    int curve;
    int column;
    double omega;
    double amplitude;
    double err;
} whirl_chart_point;
typedef struct whirl_chart_progress {
    int column, columns;
    int curves;
    long monodromies;
} whirl_chart_progress;
int whirl_chart_vertical(const whirl_chain *c, int dim, const whirl_chart_params *params,
                         int (*row)(void *, const whirl_chart_point *), void *row_data,
                         void (*tick)(void *, const whirl_chart_progress *), void *tick_data);
int whirl_chart_vertical_damped(const whirl_chain *c, int dim, const whirl_chart_params *params,
                                double air_drag, int (*row)(void *, const whirl_chart_point *),
                                void *row_data,
                                void (*tick)(void *, const whirl_chart_progress *),
                                void *tick_data);
int whirl_chart_vertical_resume(const whirl_chain *c, int dim, const whirl_chart_params *params,
                                double air_drag, const char *state,
                                int (*row)(void *, const whirl_chart_point *), void *row_data,
                                void (*tick)(void *, const whirl_chart_progress *),
                                void *tick_data, int (*save)(void *, int, const char *),
                                void *save_data);
int whirl_chart_vertical_read(const char *data, size_t size, const char *path,
                              const whirl_chart_params *params, int links, double air_drag,
                              int physical, double length, double mass, double gravity,
                              int mass_given, int (*row)(void *, const whirl_chart_point *),
                              void *row_data, int (*state)(void *, int, const char *),
                              void *state_data);
typedef struct whirl_cycle_params {
    int parameter;
    double min, max;
    int direction;
    double step;
    int max_points;
    int steps;
    double tol;
    int max_iter;
    double event_tol;
} whirl_cycle_params;
typedef struct whirl_cycle_point {
    int event;
    long index;
    double parameter;
    double omega;
    double amplitude;
    double err;
    double arclength;
    double tangent;
    double fold_test, flip_test;
    double torus_test;
    size_t count;
    const double *re, *im;
    double max_modulus, reciprocal_err;
    int verdict;
    int edge;
    double residual;
    int iterations;
    const double *y;
} whirl_cycle_point;
typedef struct whirl_cycle_progress {
    long points, events;
    double parameter;
    double step;
    int iteration;
    double residual;
} whirl_cycle_progress;
int whirl_periodic_path(whirl_periodic *w, double *y, const whirl_cycle_params *params,
                        int (*row)(void *, const whirl_cycle_point *), void *row_data,
                        void (*tick)(void *, const whirl_cycle_progress *), void *tick_data);
const char *whirl_cycle_event_name(int e);
typedef struct whirl_ellipse_chart_params {
    double radius;
    int mode;
    int side;
    double omega_min, omega_max;
    int columns;
    double e_max;
    int steps;
    double step;
    double tol;
} whirl_ellipse_chart_params;
typedef struct whirl_ellipse_point {
    int event;
    int curve;
    int column;
    double omega;
    double ellipticity;
    double err;
    double max_modulus;
} whirl_ellipse_point;
typedef struct whirl_ellipse_chart_progress {
    int column, columns;
    int curves;
    long points;
    int failed;
    double parameter;
} whirl_ellipse_chart_progress;
int whirl_chart_ellipse(const whirl_chain *c, const whirl_ellipse_chart_params *params,
                        int (*row)(void *, const whirl_ellipse_point *), void *row_data,
                        void (*tick)(void *, const whirl_ellipse_chart_progress *),
                        void *tick_data);
int whirl_chart_ellipse_resume(const whirl_chain *c, const whirl_ellipse_chart_params *params,
                               const char *state, int (*row)(void *, const whirl_ellipse_point *),
                               void *row_data,
                               void (*tick)(void *, const whirl_ellipse_chart_progress *),
                               void *tick_data, int (*save)(void *, int, const char *),
                               void *save_data);
int whirl_chart_ellipse_read(const char *data, size_t size, const char *path,
                             const whirl_ellipse_chart_params *params, int links, int physical,
                             double length, double mass, double gravity, int mass_given,
                             int (*row)(void *, const whirl_ellipse_point *), void *row_data,
                             int (*state)(void *, int, const char *), void *state_data);
const char *whirl_floquet_verdict_name(int v);
const char *whirl_floquet_edge_name(int e);
"""
STRUCTS += ["whirl_pivot_path", "whirl_scene_pivot", "whirl_periodic_params",
            "whirl_periodic_result", "whirl_chart_params", "whirl_chart_point", "whirl_chart_progress",
            "whirl_cycle_params", "whirl_cycle_point", "whirl_cycle_progress",
            "whirl_ellipse_chart_params", "whirl_ellipse_point", "whirl_ellipse_chart_progress"]
CONSTANTS += ["WHIRL_PIVOT_HARMONICS_MAX"]

CDEF += r"""
double whirl_model_stiff_rate(const whirl_model *m);
const char *whirl_model_stiff_cause(const whirl_model *m);
"""
