/* A sparse LDL^T of IPOPT's KKT systems behind MA27's four entry points, the names IPOPT loads from the
 * library its option `hsllib` names (`solve/kkt_solver.py` says why and when).
 *
 * The KKT systems of the design NLPs have a few dozen variables and a thousand or more constraint rows, each row
 * touching a few variables: eliminating a row's slack and then the row leaves a dense block of the variables and
 * the equality rows only. MUMPS spends 8-20 ms a factorisation on them, growing with the rows as one dense front
 * of all of them would, where this takes about 0.3 ms (after an order of about 2 ms, once a solve).
 *
 * - Order (at the first factorisation of a solve, from that matrix's values): first each node with a zero
 *   diagonal and a single neighbour (the slack of a row with no bounds) with that neighbour, as one 2x2 pivot
 *   block; then minimum degree over the nodes whose pivot is not zero by structure (a nonzero diagonal, or an
 *   eliminated neighbour coupled to it by a nonzero); it stops where the least degree left reaches half of what
 *   is left. The nodes not eliminated by then form the tail.
 * - Factor: the eliminated part by the up-looking sparse LDL^T along its elimination tree (static pivots, the
 *   blocks 2x2); the tail's Schur complement densely by Bunch-Kaufman (1x1 and 2x2 pivots), which copes with
 *   the zero diagonals of the equality rows and with near-singular variables. A static pivot lost to
 *   cancellation sends its node to the tail for the rest of the solve (MA27's IKEEP holds the list), and the
 *   order is made again.
 * - Inertia: the negative eigenvalues of both parts' pivots (IPOPT's INFO(15)); a singular matrix is reported
 *   so (INFO(1) = 3), and IPOPT then regularises it.
 *
 * MA27's integer and real work arrays hold everything between the calls: IW the header, order, structure
 * and elimination tree; A the input values (first NZ), then D, the blocks' couplings, L, the permuted matrix and
 * the dense tail. MA27AD only estimates their sizes; MA27BD asks for more (INFO(1) = -3 or -4, IPOPT's protocol)
 * if needed. MA27CD follows a factorisation that succeeded, as IPOPT calls it.
 *
 * IPOPT allocates IW without clearing it, once a solve, and a block an earlier solve freed can come back holding
 * that solve's header and order whole: MA27BD takes the order in IW only where IKEEP(N+1), which MA27AD clears and
 * MA27BD sets once it has written the order for this structure, says so. (Taking the header alone, a solve now
 * and then factored in an earlier solve's order, made from another matrix's values: the same designs to about
 * 1e-14, which then differed from run to run with where the allocator put the block.)
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define MAGIC_FIRST 0x4c444c54
#define MAGIC_LAST 0x6b6b7432
/* IKEEP(N+1) (of MA27's 3 N) once MA27BD has written the order of MA27AD's structure into IW */
#define ORDERED 0x6f726472
/* integer header fields at the start of IW */
enum {
    H_MAGIC_FIRST, H_N, H_NZ, H_SPARSE, H_TAIL, H_NNZ_L, H_PERM, H_LP, H_LI, H_PARENT, H_AP, H_AI, H_MAP,
    H_PAIR, H_SWAP, H_BLOCK, H_FACTORED, H_MAGIC_LAST, HEADER
};
/* Bunch-Kaufman's growth bound alpha = (1 + sqrt(17)) / 8 */
#define ALPHA 0.6403882032022076
/* the tail stays dense only up to this size; beyond it the sparse elimination continues past its stop */
#define MOST_TAIL 1500
/* a sparse pivot below this fraction of the terms it is the sum of has cancelled: its node is kept for the tail
 * and the order made again, at most MOST_REORDERS times a factorisation */
#define CANCELLED 1e-10
#define MOST_REORDERS 3

void ma27id_(int *icntl, double *cntl)
{
    memset(icntl, 0, 30 * sizeof(int));
    memset(cntl, 0, 5 * sizeof(double));
    cntl[0] = 1e-8;
}

/* ---- ordering: adjacency as bit rows (both triangles, no diagonal) ---- */

typedef struct {
    int n, words;
    uint64_t *bits;
} Graph;

static int graph(Graph *g, int n)
{
    g->n = n;
    g->words = (n + 63) / 64;
    g->bits = calloc((size_t)n * g->words, sizeof(uint64_t));
    return g->bits != NULL;
}

static inline uint64_t *bit_row(const Graph *g, int i) { return g->bits + (size_t)i * g->words; }

static inline int has_bit(const uint64_t *row, int j) { return (row[j >> 6] >> (j & 63)) & 1; }

static inline void set_bit(uint64_t *row, int j) { row[j >> 6] |= 1ULL << (j & 63); }

static inline void clear_bit(uint64_t *row, int j) { row[j >> 6] &= ~(1ULL << (j & 63)); }

static inline int ones(uint64_t x)           /* bits set (without relying on a popcount instruction) */
{
    x -= (x >> 1) & 0x5555555555555555ULL;
    x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
    x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fULL;
    return (int)((x * 0x0101010101010101ULL) >> 56);
}

static int degree(const Graph *g, int i)
{
    const uint64_t *row = bit_row(g, i);
    int d = 0;
    for (int w = 0; w < g->words; w++) d += ones(row[w]);
    return d;
}

/* The nodes in `node`'s row, into out; their count. */
static int members(const Graph *g, int node, int *out)
{
    const uint64_t *row = bit_row(g, node);
    int count = 0;
    for (int w = 0; w < g->words; w++)
        for (uint64_t bits = row[w]; bits; bits &= bits - 1) out[count++] = w * 64 + __builtin_ctzll(bits);
    return count;
}

/* `node` eliminated from g: its neighbours become a clique, and none of them links to it any more. */
static void eliminate(Graph *g, int node, const int *neighbours, int count)
{
    const uint64_t *row = bit_row(g, node);
    for (int c = 0; c < count; c++) {
        uint64_t *other = bit_row(g, neighbours[c]);
        for (int w = 0; w < g->words; w++) other[w] |= row[w];
        clear_bit(other, neighbours[c]);
        clear_bit(other, node);
    }
}

static void enqueue(int *head, int *next, int *previous, char *queued, const int *deg, int i)
{
    next[i] = head[deg[i]];
    previous[i] = -1;
    if (head[deg[i]] >= 0) previous[head[deg[i]]] = i;
    head[deg[i]] = i;
    queued[i] = 1;
}

static void dequeue(int *head, int *next, int *previous, char *queued, const int *deg, int i)
{
    if (previous[i] >= 0) next[previous[i]] = next[i];
    else head[deg[i]] = next[i];
    if (next[i] >= 0) previous[next[i]] = previous[i];
    queued[i] = 0;
}

/* Elimination order into perm (new -> old); returns how many lead it as the sparse part, or -1 (no memory).
 * `linked` holds every entry; `strong` those with a nonzero value (an entry of the matrix that is nonzero now,
 * or fill from two of them): a node's pivot is zero by structure until a strong neighbour is eliminated.
 * Nodes marked in `kept` never pivot in the sparse part. pair[k] is 1 and 2 at the two positions of a 2x2
 * block, 0 elsewhere. */
static int order(int n, int nz, const int *irn, const int *icn, const double *a, const int *kept, int *perm,
                 int *pair)
{
    Graph linked, strong;
    int ok_linked = graph(&linked, n), ok_strong = graph(&strong, n);
    char *pivotable = calloc(n, 1), *done = calloc(n, 1), *queued = calloc(n, 1), *stale = calloc(n, 1);
    int *deg = malloc(n * sizeof(int)), *neighbours = malloc(n * sizeof(int)), *head = malloc((n + 1) * sizeof(int));
    int *next = malloc(n * sizeof(int)), *previous = malloc(n * sizeof(int));
    double *diagonal = calloc(n, sizeof(double));
    int sparse = -1;
    if (!ok_linked || !ok_strong || !pivotable || !done || !queued || !stale || !deg || !neighbours || !head || !next ||
        !previous || !diagonal)
        goto out;
    for (int e = 0; e < nz; e++) {
        int i = irn[e] - 1, j = icn[e] - 1;
        if (i == j) {
            diagonal[i] += a[e];
            continue;
        }
        set_bit(bit_row(&linked, i), j);
        set_bit(bit_row(&linked, j), i);
        if (a[e] != 0.0) {
            set_bit(bit_row(&strong, i), j);
            set_bit(bit_row(&strong, j), i);
        }
    }
    for (int i = 0; i < n; i++) pivotable[i] = diagonal[i] != 0.0 && !kept[i];
    /* pairs first: a node s with a zero diagonal and one neighbour r (the slack of a row with no bounds, whose
     * pivot would be zero either way) is eliminated with r as one 2x2 block [[0, c], [c, a_r]]; it adds
     * a_s / det to the pivots of r's neighbours, nothing while a_s = 0 */
    int k = 0;
    for (int i = 0; i < n; i++) {
        if (done[i] || kept[i] || diagonal[i] != 0.0 || degree(&linked, i) != 1) continue;
        members(&linked, i, neighbours);
        int r = neighbours[0];
        if (done[r] || kept[r] || !has_bit(bit_row(&strong, i), r)) continue;
        pair[k] = 1;
        perm[k++] = i;
        pair[k] = 2;
        perm[k++] = r;
        done[i] = done[r] = 1;
        clear_bit(bit_row(&linked, r), i);
        int count = members(&linked, r, neighbours);
        eliminate(&linked, r, neighbours, count);
        for (int c = 0; c < count; c++) clear_bit(bit_row(&strong, neighbours[c]), r);     /* no fill: a_s = 0 */
    }
    /* the pivotable nodes not yet eliminated, in lists by degree (head[d], then next) */
    for (int d = 0; d <= n; d++) head[d] = -1;
    for (int i = 0; i < n; i++) {
        deg[i] = degree(&linked, i);
        queued[i] = 0;
        if (pivotable[i] && !done[i]) enqueue(head, next, previous, queued, deg, i);
    }
    int least = 0;
    for (; k < n; k++) {
        int best = -1;
        while (best < 0) {                       /* a stale degree is a lower bound: made exact at the head */
            while (least <= n && head[least] < 0) least++;
            if (least > n) break;
            best = head[least];
            if (stale[best]) {
                dequeue(head, next, previous, queued, deg, best);
                deg[best] = degree(&linked, best);
                stale[best] = 0;
                enqueue(head, next, previous, queued, deg, best);
                best = -1;
            }
        }
        int left = n - k;
        if (best < 0 || (2 * least >= left && left <= MOST_TAIL)) break;
        dequeue(head, next, previous, queued, deg, best);
        perm[k] = best;
        pair[k] = 0;
        done[best] = 1;
        const uint64_t *strong_row = bit_row(&strong, best);
        int count = members(&linked, best, neighbours);
        for (int c = 0; c < count; c++) {        /* fill from two nonzeros is a nonzero, and makes a pivot one */
            int u = neighbours[c];
            uint64_t *other_strong = bit_row(&strong, u);
            if (has_bit(strong_row, u)) {
                for (int w = 0; w < strong.words; w++) other_strong[w] |= strong_row[w];
                clear_bit(other_strong, u);
                pivotable[u] = !kept[u];
            }
            clear_bit(other_strong, best);
        }
        eliminate(&linked, best, neighbours, count);
        for (int c = 0; c < count; c++) {        /* a neighbour loses one and may gain up to count - 1 */
            int u = neighbours[c];
            if (queued[u]) dequeue(head, next, previous, queued, deg, u);
            deg[u] = deg[u] > 0 ? deg[u] - 1 : 0;
            stale[u] = 1;
            if (pivotable[u]) {
                enqueue(head, next, previous, queued, deg, u);
                if (deg[u] < least) least = deg[u];
            }
        }
    }
    sparse = k;
    for (int i = 0; i < n; i++)
        if (!done[i]) perm[k++] = i;
out:
    free(linked.bits);
    free(strong.bits);
    free(pivotable);
    free(done);
    free(queued);
    free(stale);
    free(deg);
    free(neighbours);
    free(head);
    free(next);
    free(previous);
    free(diagonal);
    return sparse;
}

void ma27ad_(int *N, int *NZ, const int *IRN, const int *ICN, int *IW, int *LIW, int *IKEEP, int *IW1,
             int *NSTEPS, int *IFLAG, int *ICNTL, double *CNTL, int *INFO, double *OPS)
{
    int n = *N, nz = *NZ;
    (void)IW, (void)LIW, (void)IW1, (void)IFLAG, (void)ICNTL, (void)CNTL;
    memset(INFO, 0, 20 * sizeof(int));
    for (int e = 0; e < nz; e++)
        if (IRN[e] < 1 || IRN[e] > n || ICN[e] < 1 || ICN[e] > n) {
            INFO[0] = 1;
            return;
        }
    *NSTEPS = 1;
    *OPS = 0.0;
    memset(IKEEP, 0, n * sizeof(int));           /* no node kept for the tail yet (MA27BD) */
    if (n > 0) IKEEP[n] = 0;                     /* and no order in IW */
    long guess = 2L * nz + 4L * n + 10000;     /* entries of L and of the dense tail; MA27BD asks for more */
    INFO[4] = (int)(2L * nz + n + guess);
    INFO[5] = (int)(HEADER + 5L * n + 2L * nz + guess);
}

/* Order, permuted upper triangle (CSC, a slot per input entry), elimination tree of the sparse part and its
 * column counts, written into iw when it fits: 1, or -1 with the sizes needed, or 0 (no memory). */
static int analyse(int n, int nz, const int *irn, const int *icn, const double *a, const int *kept, int *iw,
                   int liw, int la, int *need_iw, int *need_a)
{
    int *perm = malloc(n * sizeof(int)), *position = malloc(n * sizeof(int));
    int *ap = calloc(n + 1, sizeof(int)), *ai = malloc((nz + 1) * sizeof(int)), *slot = malloc((nz + 1) * sizeof(int));
    int *next = malloc(n * sizeof(int)), *flag = malloc(n * sizeof(int)), *parent = malloc(n * sizeof(int));
    int *lnz = calloc(n, sizeof(int)), *pair = calloc(n, sizeof(int));
    int result = 0;
    if (!perm || !position || !ap || !ai || !slot || !next || !flag || !parent || !lnz || !pair) goto out;
    int sparse = order(n, nz, irn, icn, a, kept, perm, pair);
    if (sparse < 0) goto out;
    int tail = n - sparse;
    for (int k = 0; k < n; k++) position[perm[k]] = k;
    for (int e = 0; e < nz; e++) {
        int i = position[irn[e] - 1], j = position[icn[e] - 1];
        ap[(i > j ? i : j) + 1]++;
    }
    for (int k = 0; k < n; k++) ap[k + 1] += ap[k];
    memcpy(next, ap, n * sizeof(int));
    for (int e = 0; e < nz; e++) {
        int i = position[irn[e] - 1], j = position[icn[e] - 1];
        int column = i > j ? i : j;
        slot[e] = next[column];
        ai[next[column]++] = i > j ? j : i;
    }
    /* row k's pattern in the sparse columns: the paths up the tree from its entries (a tail row sets no parent) */
    for (int k = 0; k < n; k++) {
        if (k < sparse) parent[k] = -1;
        flag[k] = k;
        for (int p = ap[k]; p < ap[k + 1]; p++) {
            if (k < sparse && pair[k] == 2 && ai[p] == k - 1) continue;      /* inside a 2x2 block */
            for (int i = ai[p]; i < sparse && flag[i] != k; i = parent[i]) {
                if (parent[i] == -1 && k < sparse) parent[i] = k;
                lnz[i]++;
                if (pair[i] == 2) lnz[i - 1]++;                             /* the block's first column */
                flag[i] = k;
                if (parent[i] == -1) break;
            }
        }
    }
    long nnz_l = 0;
    for (int k = 0; k < sparse; k++) nnz_l += lnz[k];
    long words = HEADER + n + (sparse + 1) + nnz_l + sparse + (n + 1) + nz + nz + 2L * tail + sparse;
    long reals = (long)nz + 2L * sparse + nnz_l + nz + (long)tail * tail;
    *need_iw = (int)words;
    *need_a = (int)reals;
    if (words > liw || reals > la) {
        result = -1;
        goto out;
    }
    int at = HEADER;
    iw[H_PERM] = at;
    memcpy(iw + at, perm, n * sizeof(int));
    at += n;
    iw[H_LP] = at;
    iw[at] = 0;
    for (int k = 0; k < sparse; k++) iw[at + k + 1] = iw[at + k] + lnz[k];
    at += sparse + 1;
    iw[H_LI] = at;
    at += (int)nnz_l;
    iw[H_PARENT] = at;
    memcpy(iw + at, parent, sparse * sizeof(int));
    at += sparse;
    iw[H_AP] = at;
    memcpy(iw + at, ap, (n + 1) * sizeof(int));
    at += n + 1;
    iw[H_AI] = at;
    memcpy(iw + at, ai, nz * sizeof(int));
    at += nz;
    iw[H_MAP] = at;
    memcpy(iw + at, slot, nz * sizeof(int));
    at += nz;
    iw[H_PAIR] = at;
    memcpy(iw + at, pair, sparse * sizeof(int));
    at += sparse;
    iw[H_SWAP] = at;
    at += tail;
    iw[H_BLOCK] = at;
    iw[H_N] = n;
    iw[H_NZ] = nz;
    iw[H_SPARSE] = sparse;
    iw[H_TAIL] = tail;
    iw[H_NNZ_L] = (int)nnz_l;
    iw[H_MAGIC_FIRST] = MAGIC_FIRST;
    iw[H_MAGIC_LAST] = MAGIC_LAST;
    result = 1;
out:
    free(perm);
    free(position);
    free(ap);
    free(ai);
    free(slot);
    free(next);
    free(flag);
    free(parent);
    free(lnz);
    free(pair);
    return result;
}

static void swap_symmetric(double *s, int t, int i, int j)
{
    if (i == j) return;
    for (int c = 0; c < t; c++) {
        double v = s[i * t + c];
        s[i * t + c] = s[j * t + c];
        s[j * t + c] = v;
    }
    for (int r = 0; r < t; r++) {
        double v = s[r * t + i];
        s[r * t + i] = s[r * t + j];
        s[r * t + j] = v;
    }
}

/* Bunch-Kaufman of the dense symmetric s (t x t, full): P s P^T = L D L^T with L below the diagonal, D's 1x1
 * and 2x2 blocks on it (block[k] = 1, or 2 then 0); swap[k] the row exchanged with k at step k. Returns the
 * negative eigenvalues of D, or -1 - (the step) where a whole column is zero. */
static int bunch_kaufman(double *s, int t, int *swap, int *block)
{
    int negative = 0;
    for (int k = 0; k < t;) {
        double diagonal = fabs(s[k * t + k]), column = 0.0;
        int r = k;
        for (int i = k + 1; i < t; i++)
            if (fabs(s[i * t + k]) > column) column = fabs(s[i * t + k]), r = i;
        if (diagonal == 0.0 && column == 0.0) return -1 - k;
        int size = 1, exchange = k;
        if (diagonal < ALPHA * column) {
            double row = 0.0;
            for (int j = k; j < t; j++)
                if (j != r && fabs(s[r * t + j]) > row) row = fabs(s[r * t + j]);
            if (diagonal * row >= ALPHA * column * column) {
                exchange = k;
            } else if (fabs(s[r * t + r]) >= ALPHA * row) {
                exchange = r;
            } else {
                size = 2;
                exchange = r;
            }
        }
        if (size == 1) {
            swap_symmetric(s, t, k, exchange);
            swap[k] = exchange;
            block[k] = 1;
            double d = s[k * t + k];
            if (d < 0) negative++;
            for (int i = k + 1; i < t; i++) {
                double l = s[i * t + k] / d;
                for (int j = k + 1; j < t; j++) s[i * t + j] -= l * s[j * t + k];
            }
            for (int i = k + 1; i < t; i++) s[i * t + k] /= d;
        } else {
            swap_symmetric(s, t, k + 1, exchange);
            swap[k] = k;
            swap[k + 1] = exchange;
            block[k] = 2;
            block[k + 1] = 0;
            double a = s[k * t + k], b = s[(k + 1) * t + k], c = s[(k + 1) * t + k + 1], det = a * c - b * b;
            negative += det < 0 ? 1 : (a < 0 ? 2 : 0);
            for (int i = k + 2; i < t; i++) {
                double w1 = s[i * t + k], w2 = s[i * t + k + 1];
                double l1 = (c * w1 - b * w2) / det, l2 = (a * w2 - b * w1) / det;
                for (int j = k + 2; j < t; j++) s[i * t + j] -= l1 * s[j * t + k] + l2 * s[j * t + k + 1];
            }
            for (int i = k + 2; i < t; i++) {
                double w1 = s[i * t + k], w2 = s[i * t + k + 1];
                s[i * t + k] = (c * w1 - b * w2) / det;
                s[i * t + k + 1] = (a * w2 - b * w1) / det;
            }
        }
        k += size;
    }
    return negative;
}

/* Numeric factorisation in the order iw holds: 0, or 1 + the position of a sparse pivot lost to cancellation
 * (below CANCELLED of the terms it came from), or -1 where the tail is singular, or -2 (no memory). */
static int factor(int n, int nz, double *a, int *iw, int *negative)
{
    int sparse = iw[H_SPARSE], tail = iw[H_TAIL], nnz_l = iw[H_NNZ_L];
    const int *lp = iw + iw[H_LP], *parent = iw + iw[H_PARENT], *ap = iw + iw[H_AP], *ai = iw + iw[H_AI];
    const int *map = iw + iw[H_MAP], *pair = iw + iw[H_PAIR];
    int *li = iw + iw[H_LI];
    double *d = a + nz, *coupling = d + sparse, *lx = coupling + sparse, *ax = lx + nnz_l, *schur = ax + nz;
    double *y = calloc(n, sizeof(double));
    int *pattern = malloc(n * sizeof(int)), *flag = malloc(n * sizeof(int)), *lnz = calloc(sparse + 1, sizeof(int));
    int result = 0;
    *negative = 0;
    if (!y || !pattern || !flag || !lnz) {
        result = -2;
        goto out;
    }
    memset(ax, 0, nz * sizeof(double));
    for (int e = 0; e < nz; e++) ax[map[e]] += a[e];
    for (int k = 0; k < n; k++) {
        int top = n;
        double size = 0.0;
        flag[k] = k;
        double within = 0.0;                     /* a 2x2 block's own coupling c, at its second row */
        for (int p = ap[k]; p < ap[k + 1]; p++) {
            int i = ai[p], length = 0;
            if (k < sparse && pair[k] == 2 && i == k - 1) {
                within += ax[p];
                continue;
            }
            y[i] += ax[p];
            if (i == k) size += fabs(ax[p]);
            for (; i < sparse && flag[i] != k; i = parent[i]) {
                pattern[length++] = i;
                flag[i] = k;
                if (parent[i] == -1) break;
            }
            while (length > 0) pattern[--top] = pattern[--length];
        }
        for (; top < n; top++) {                 /* the sparse columns of row k, along the tree */
            int i = pattern[top], end = lp[i] + lnz[i];
            double yi = y[i], l = yi / d[i];
            y[i] = 0.0;
            for (int p = lp[i]; p < end; p++) y[li[p]] -= lx[p] * yi;
            if (pair[i] == 2) {                  /* block (s, i): row k has nothing at s, so only r's part */
                int first = i - 1, end_first = lp[first] + lnz[first];
                double det = d[first] * d[i] - coupling[first] * coupling[first];
                l = yi * d[first] / det;
                li[end_first] = k;
                lx[end_first] = -coupling[first] * yi / det;
                lnz[first]++;
            }
            y[k] -= l * yi;
            size += fabs(l * yi);
            li[end] = k;
            lx[end] = l;
            lnz[i]++;
        }
        if (k < sparse && pair[k] == 1) {       /* a block's first pivot: judged with its second */
            d[k] = y[k];
            y[k] = 0.0;
        } else if (k < sparse && pair[k] == 2) {
            d[k] = y[k];
            y[k] = 0.0;
            coupling[k - 1] = within;
            double det = d[k - 1] * d[k] - within * within;
            if (!(fabs(det) > CANCELLED * (fabs(d[k - 1] * d[k]) + within * within)) || !isfinite(det)) {
                result = 1 + k;
                goto out;
            }
            *negative += det < 0 ? 1 : (d[k] < 0 ? 2 : 0);
        } else if (k < sparse) {
            double dk = y[k];
            y[k] = 0.0;
            if (!(fabs(dk) > CANCELLED * size) || !isfinite(dk)) {
                result = 1 + k;
                goto out;
            }
            if (dk < 0) ++*negative;
            d[k] = dk;
        } else {                                 /* row k - sparse of the tail's Schur complement */
            for (int j = sparse; j <= k; j++) {
                schur[(long)(k - sparse) * tail + (j - sparse)] = y[j];
                schur[(long)(j - sparse) * tail + (k - sparse)] = y[j];
                y[j] = 0.0;
            }
        }
    }
    if (tail > 0) {
        int found = bunch_kaufman(schur, tail, iw + iw[H_SWAP], iw + iw[H_BLOCK]);
        if (found < 0) result = -1;
        else *negative += found;
    }
out:
    free(y);
    free(pattern);
    free(flag);
    free(lnz);
    return result;
}

void ma27bd_(int *N, int *NZ, const int *IRN, const int *ICN, double *A, int *LA, int *IW, int *LIW, int *IKEEP,
             int *NSTEPS, int *MAXFRT, int *IW1, int *ICNTL, double *CNTL, int *INFO)
{
    int n = *N, nz = *NZ, *kept = IKEEP;         /* nodes kept for the tail since a pivot of theirs cancelled */
    (void)NSTEPS, (void)IW1, (void)ICNTL, (void)CNTL;
    memset(INFO, 0, 20 * sizeof(int));
    *MAXFRT = n > 0 ? n : 1;
    for (int attempt = 0; attempt <= MOST_REORDERS; attempt++) {
        int known = n > 0 && IKEEP[n] == ORDERED && *LIW >= HEADER && IW[H_MAGIC_FIRST] == MAGIC_FIRST &&
                    IW[H_MAGIC_LAST] == MAGIC_LAST && IW[H_N] == n && IW[H_NZ] == nz;
        if (!known) {
            int need_iw, need_a;
            int analysed = analyse(n, nz, IRN, ICN, A, kept, IW, *LIW, *LA, &need_iw, &need_a);
            if (analysed == 0) {
                INFO[0] = -5;
                return;
            }
            if (analysed < 0) {
                INFO[0] = need_iw > *LIW ? -3 : -4;
                INFO[1] = need_iw > *LIW ? need_iw : need_a;
                return;
            }
            if (n > 0) IKEEP[n] = ORDERED;
        }
        /* the input values stay in A[0, nz) for a new order: the factor is written after them */
        int negative, outcome = factor(n, nz, A, IW, &negative);
        IW[H_FACTORED] = outcome == 0;
        if (outcome == -2) {
            INFO[0] = -5;
            return;
        }
        if (outcome > 0 && attempt < MOST_REORDERS) {
            kept[IW[IW[H_PERM] + outcome - 1]] = 1;
            IKEEP[n] = 0;                        /* ordered again, with that node in the tail */
            continue;
        }
        INFO[14] = negative;
        if (outcome != 0) {                      /* singular to working precision: IPOPT regularises */
            INFO[0] = 3;
            INFO[1] = n - 1;
        }
        return;
    }
}

void ma27cd_(int *N, double *A, int *LA, int *IW, int *LIW, double *W, int *MAXFRT, double *RHS, int *IW1,
             int *NSTEPS, int *ICNTL, int *INFO)
{
    int n = *N, nz = IW[H_NZ], sparse = IW[H_SPARSE], tail = IW[H_TAIL], nnz_l = IW[H_NNZ_L];
    (void)LA, (void)LIW, (void)MAXFRT, (void)IW1, (void)NSTEPS, (void)ICNTL, (void)INFO;
    if (!IW[H_FACTORED]) return;                /* IPOPT solves only after a factorisation that succeeded */
    const int *perm = IW + IW[H_PERM], *lp = IW + IW[H_LP], *li = IW + IW[H_LI];
    const int *swap = IW + IW[H_SWAP], *block = IW + IW[H_BLOCK], *pair = IW + IW[H_PAIR];
    const double *d = A + nz, *coupling = d + sparse, *lx = coupling + sparse, *s = lx + nnz_l + nz;
    for (int k = 0; k < n; k++) W[k] = RHS[perm[k]];
    for (int j = 0; j < sparse; j++) {
        double wj = W[j];
        for (int p = lp[j]; p < lp[j + 1]; p++) W[li[p]] -= lx[p] * wj;
    }
    for (int k = 0; k < sparse; k++) {
        if (pair[k] == 1) {                      /* a 2x2 block [[d_s, c], [c, d_r]] */
            double c = coupling[k], det = d[k] * d[k + 1] - c * c, u = W[k], v = W[k + 1];
            W[k] = (d[k + 1] * u - c * v) / det;
            W[k + 1] = (d[k] * v - c * u) / det;
            k++;
        } else {
            W[k] /= d[k];
        }
    }
    double *x = W + sparse;                       /* the tail: P S P^T = L D L^T */
    for (int k = 0; k < tail; k++) {
        double v = x[k];
        x[k] = x[swap[k]];
        x[swap[k]] = v;
    }
    for (int k = 0; k < tail; k++) {
        int first = block[k] == 0 ? k + 1 : k + block[k];
        for (int i = first; i < tail; i++) x[i] -= s[i * tail + k] * x[k];
    }
    for (int k = 0; k < tail; k++) {
        if (block[k] == 1) {
            x[k] /= s[k * tail + k];
        } else if (block[k] == 2) {
            double a = s[k * tail + k], b = s[(k + 1) * tail + k], c = s[(k + 1) * tail + k + 1];
            double det = a * c - b * b, u = x[k], v = x[k + 1];
            x[k] = (c * u - b * v) / det;
            x[k + 1] = (a * v - b * u) / det;
        }
    }
    for (int k = tail - 1; k >= 0; k--) {
        int first = block[k] == 0 ? k + 1 : k + block[k];
        for (int i = first; i < tail; i++) x[k] -= s[i * tail + k] * x[i];
    }
    for (int k = tail - 1; k >= 0; k--) {
        double v = x[k];
        x[k] = x[swap[k]];
        x[swap[k]] = v;
    }
    for (int j = sparse - 1; j >= 0; j--) {
        double sum = W[j];
        for (int p = lp[j]; p < lp[j + 1]; p++) sum -= lx[p] * W[li[p]];
        W[j] = sum;
    }
    for (int k = 0; k < n; k++) RHS[perm[k]] = W[k];
}

/* importable, so that the package can find the library's file without loading it into IPOPT first */
static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_sparse_ldl", NULL, -1, NULL};

PyMODINIT_FUNC PyInit__sparse_ldl(void) { return PyModule_Create(&module); }
