/* TCP transport of the bearing FMU's native layer (bearing_tcp.h). */
#ifdef _WIN32
#define WIN32_LEAN_AND_MEAN
#include <winsock2.h>
#include <ws2tcpip.h>
#include <mstcpip.h>
#include <windows.h>
typedef SOCKET sock_t;
#define BAD_SOCK INVALID_SOCKET
#define close_sock closesocket
#define sock_errno() WSAGetLastError()
#else
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <time.h>
#include <unistd.h>
typedef int sock_t;
#define BAD_SOCK (-1)
#define close_sock close
#define sock_errno() errno
#endif
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bearing_tcp.h"

#define FRAME_MAX (32u << 20) /* the largest response accepted [bytes] */
#define REPLY_MAX 4096u       /* the largest handshake reply */
#define FAULT_MAX 65536u      /* the largest fault text */

#define STAGE 65536u /* received bytes not yet consumed: a frame usually arrives whole, in one recv */

struct BTcp {
    sock_t s;
    char peer[300];
    unsigned char stage[STAGE];
    size_t have, used; /* stage[used..have) are received and not consumed */
#ifdef _WIN32
    DWORD rcvtimeo; /* the SO_RCVTIMEO now set [ms] */
#endif
};

static double mono(void) {
#ifdef _WIN32
    LARGE_INTEGER f, c;
    QueryPerformanceFrequency(&f);
    QueryPerformanceCounter(&c);
    return (double)c.QuadPart / (double)f.QuadPart;
#else
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
#endif
}

static void sock_msg(int e, char *out, size_t n) {
#ifdef _WIN32
    if (!FormatMessageA(FORMAT_MESSAGE_FROM_SYSTEM | FORMAT_MESSAGE_IGNORE_INSERTS, NULL, (DWORD)e, 0, out, (DWORD)n,
                        NULL))
        snprintf(out, n, "error %d", e);
    size_t k = strlen(out);
    while (k && (out[k - 1] == '\n' || out[k - 1] == '\r' || out[k - 1] == '.')) out[--k] = '\0';
#else
    snprintf(out, n, "%s", strerror(e));
#endif
}

/* Waits until s is readable (or writable); 1 ready, 0 timeout, -1 error. */
static int wait_sock(sock_t s, int write, double seconds) {
    int ms = seconds <= 0 ? 0 : seconds > 2e6 ? 2000000000 : (int)(seconds * 1000.0) + 1;
#ifdef _WIN32
    WSAPOLLFD p;
    p.fd = s;
    p.events = write ? POLLWRNORM : POLLRDNORM;
    p.revents = 0;
    int r = WSAPoll(&p, 1, ms);
#else
    struct pollfd p = {s, (short)(write ? POLLOUT : POLLIN), 0};
    int r;
    do r = poll(&p, 1, ms); while (r < 0 && errno == EINTR);
#endif
    return r < 0 ? -1 : r > 0;
}

static int send_all(BTcp *t, const unsigned char *p, size_t n, char *err, size_t nerr) {
    while (n) {
#ifdef _WIN32
        int k = send(t->s, (const char *)p, n > 1u << 30 ? 1 << 30 : (int)n, 0);
#else
        ssize_t k = send(t->s, p, n, MSG_NOSIGNAL);
        if (k < 0 && errno == EINTR) continue;
#endif
        if (k <= 0) {
            char m[200];
            sock_msg(sock_errno(), m, sizeof m);
            snprintf(err, nerr, "the connection to the model server at %s failed while sending (%s)", t->peer, m);
            return -1;
        }
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

/* a and b in one call (scatter-gather) when the socket takes them whole, else the rest by send_all */
static int send_two(BTcp *t, const unsigned char *a, size_t na, const unsigned char *b, size_t nb, char *err,
                    size_t nerr) {
    size_t sent = 0;
#ifdef _WIN32
    WSABUF v[2] = {{(ULONG)na, (CHAR *)a}, {(ULONG)nb, (CHAR *)b}};
    DWORD k = 0;
    if (nb < (1u << 30) && WSASend(t->s, v, nb ? 2 : 1, &k, 0, NULL, NULL) == 0) sent = k;
#else
    struct iovec v[2] = {{(void *)a, na}, {(void *)b, nb}};
    struct msghdr m;
    memset(&m, 0, sizeof m);
    m.msg_iov = v;
    m.msg_iovlen = nb ? 2 : 1;
    ssize_t k = sendmsg(t->s, &m, MSG_NOSIGNAL);
    if (k > 0) sent = (size_t)k;
#endif
    if (sent < na && send_all(t, a + sent, na - sent, err, nerr) != 0) return -1;
    size_t off = sent > na ? sent - na : 0;
    return nb > off ? send_all(t, b + off, nb - off, err, nerr) : 0;
}

/* One recv of what is there into the stage (waiting until the deadline): 0; -1 closed or failed, -2 timeout.
 * On Windows a blocking recv with a receive timeout (one call; a poll before each recv costs a round trip to
 * the wine server under wine). */
static int fill(BTcp *t, double deadline, char *err, size_t nerr) {
    if (t->used == t->have) t->used = t->have = 0;
    else if (t->used > STAGE / 2) {
        memmove(t->stage, t->stage + t->used, t->have - t->used);
        t->have -= t->used;
        t->used = 0;
    }
    for (;;) {
        double left = deadline - mono();
        if (left <= 0) {
            snprintf(err, nerr, "timeout");
            return -2;
        }
#ifdef _WIN32
        DWORD ms = left > 2e6 ? 2000000000u : (DWORD)(left * 1000.0) + 1;
        if (ms > t->rcvtimeo + 50 || ms + 50 < t->rcvtimeo) { /* re-set only when it changed noticeably */
            setsockopt(t->s, SOL_SOCKET, SO_RCVTIMEO, (const char *)&ms, sizeof ms);
            t->rcvtimeo = ms;
        }
        int k = recv(t->s, (char *)t->stage + t->have, (int)(STAGE - t->have), 0);
        if (k < 0 && WSAGetLastError() == WSAETIMEDOUT) continue;
#else
        int w = wait_sock(t->s, 0, left);
        if (w == 0) continue;
        ssize_t k = w < 0 ? -1 : recv(t->s, t->stage + t->have, STAGE - t->have, 0);
        if (k < 0 && errno == EINTR) continue;
#endif
        if (k == 0) {
            snprintf(err, nerr, "the model server at %s closed the connection (the server was stopped or killed, "
                     "or the network failed)", t->peer);
            return -1;
        }
        if (k < 0) {
            char m[200];
            sock_msg(sock_errno(), m, sizeof m);
            snprintf(err, nerr, "the connection to the model server at %s failed (%s): the server or its model "
                     "process was stopped or killed, or the network failed", t->peer, m);
            return -1;
        }
        t->have += (size_t)k;
        return 0;
    }
}

/* n bytes by the deadline: 0; -1 closed or failed, -2 timeout (err set). */
static int recv_all(BTcp *t, unsigned char *p, size_t n, double deadline, char *err, size_t nerr) {
    while (n) {
        if (t->used == t->have) {
            int r = fill(t, deadline, err, nerr);
            if (r != 0) return r;
        }
        size_t k = t->have - t->used < n ? t->have - t->used : n;
        memcpy(p, t->stage + t->used, k);
        t->used += k;
        p += k;
        n -= k;
    }
    return 0;
}

static void put32(unsigned char *p, uint32_t v) { memcpy(p, &v, 4); }
static uint32_t get32(const unsigned char *p) { uint32_t v; memcpy(&v, p, 4); return v; }

static void keepalive(sock_t s) {
    int one = 1;
    setsockopt(s, IPPROTO_TCP, TCP_NODELAY, (const char *)&one, sizeof one);
    setsockopt(s, SOL_SOCKET, SO_KEEPALIVE, (const char *)&one, sizeof one);
#ifdef _WIN32
    struct tcp_keepalive ka = {1, 30000, 10000};
    DWORD ret = 0;
    WSAIoctl(s, SIO_KEEPALIVE_VALS, &ka, sizeof ka, NULL, 0, &ret, NULL, NULL);
#else
#ifdef TCP_KEEPIDLE
    int idle = 30, intvl = 10, cnt = 3;
    setsockopt(s, IPPROTO_TCP, TCP_KEEPIDLE, &idle, sizeof idle);
    setsockopt(s, IPPROTO_TCP, TCP_KEEPINTVL, &intvl, sizeof intvl);
    setsockopt(s, IPPROTO_TCP, TCP_KEEPCNT, &cnt, sizeof cnt);
#endif
#endif
}

/* Non-blocking connect with a deadline; the socket is left blocking. */
static sock_t dial(const char *host, const char *port, double timeout, char *err, size_t nerr) {
    struct addrinfo hints, *res = NULL;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    int g = getaddrinfo(host, port, &hints, &res);
    if (g != 0 || !res) {
        snprintf(err, nerr, "cannot resolve %s (%s)", host, gai_strerror(g));
        return BAD_SOCK;
    }
    sock_t s = BAD_SOCK;
    char why[200] = "no address";
    for (struct addrinfo *a = res; a; a = a->ai_next) {
        s = socket(a->ai_family, a->ai_socktype, a->ai_protocol);
        if (s == BAD_SOCK) continue;
#ifdef _WIN32
        u_long nb = 1;
        ioctlsocket(s, FIONBIO, &nb);
        int r = connect(s, a->ai_addr, (int)a->ai_addrlen);
        int pending = r != 0 && WSAGetLastError() == WSAEWOULDBLOCK;
#else
        fcntl(s, F_SETFD, FD_CLOEXEC);
        int fl = fcntl(s, F_GETFL);
        fcntl(s, F_SETFL, fl | O_NONBLOCK);
        int r = connect(s, a->ai_addr, a->ai_addrlen);
        int pending = r != 0 && errno == EINPROGRESS;
#endif
        if (r == 0 || (pending && wait_sock(s, 1, timeout) == 1)) {
            int e = 0;
            socklen_t len = sizeof e;
            getsockopt(s, SOL_SOCKET, SO_ERROR, (char *)&e, &len);
            if (e == 0) {
#ifdef _WIN32
                nb = 0;
                ioctlsocket(s, FIONBIO, &nb);
#else
                fcntl(s, F_SETFL, fl);
#endif
                freeaddrinfo(res);
                return s;
            }
            sock_msg(e, why, sizeof why);
        } else if (pending) {
            snprintf(why, sizeof why, "no answer within %g s", timeout);
        } else {
            sock_msg(sock_errno(), why, sizeof why);
        }
        close_sock(s);
        s = BAD_SOCK;
    }
    freeaddrinfo(res);
    snprintf(err, nerr, "%s", why);
    return BAD_SOCK;
}

BTcp *btcp_connect(const char *hostport, const char *token, uint32_t protocol, const char *guid, double timeout,
                   char *err, size_t nerr) {
#ifdef _WIN32
    static int wsa_ok = 0;
    if (!wsa_ok) {
        WSADATA w;
        if (WSAStartup(MAKEWORD(2, 2), &w) != 0) {
            snprintf(err, nerr, "WSAStartup failed");
            return NULL;
        }
        wsa_ok = 1;
    }
#endif
    char host[256], port[16];
    const char *colon = strrchr(hostport, ':');
    size_t hl = colon ? (size_t)(colon - hostport) : 0;
    if (!colon || hl == 0 || hl >= sizeof host || strlen(colon + 1) == 0 || strlen(colon + 1) >= sizeof port) {
        snprintf(err, nerr, "BEARING_FMU_SERVER = '%s' is invalid; allowed: host:port, e.g. %s", hostport,
                 BTCP_DEFAULT_SERVER);
        return NULL;
    }
    memcpy(host, hostport, hl);
    host[hl] = '\0';
    if (host[0] == '[' && hl > 2 && host[hl - 1] == ']') { /* [IPv6]:port */
        memmove(host, host + 1, hl - 2);
        host[hl - 2] = '\0';
    }
    snprintf(port, sizeof port, "%s", colon + 1);
    size_t tl = token ? strlen(token) : 0, gl = guid ? strlen(guid) : 0;
    if (tl > 1024 || gl > 1024) {
        snprintf(err, nerr, "%s is longer than 1024 bytes", tl > 1024 ? "BEARING_FMU_TOKEN" : "the GUID");
        return NULL;
    }
    BTcp *t = (BTcp *)calloc(1, sizeof(BTcp));
    if (!t) {
        snprintf(err, nerr, "out of memory");
        return NULL;
    }
    snprintf(t->peer, sizeof t->peer, "%s", hostport);
    char why[300];
    t->s = dial(host, port, timeout < 10.0 ? timeout : 10.0, why, sizeof why);
    if (t->s == BAD_SOCK) {
        snprintf(err, nerr, "cannot connect to the model server at %s (%s)", hostport, why);
        free(t);
        return NULL;
    }
    keepalive(t->s);
    /* both handshake frames at once: the token first (the server checks it before reading on) */
    unsigned char hello[2 * 1024 + 32];
    unsigned char *p = hello;
    put32(p, (uint32_t)(8 + tl));
    memcpy(p + 4, "BRGT", 4);
    put32(p + 8, (uint32_t)tl);
    if (tl) memcpy(p + 12, token, tl);
    p += 12 + tl;
    put32(p, (uint32_t)(8 + gl));
    put32(p + 4, protocol);
    put32(p + 8, (uint32_t)gl);
    if (gl) memcpy(p + 12, guid, gl);
    p += 12 + gl;
    unsigned char head[8];
    if (timeout > 30.0) timeout = 30.0; /* a model server answers the handshake at once */
    double deadline = mono() + timeout;
    int r = send_all(t, hello, (size_t)(p - hello), err, nerr);
    if (r == 0) r = recv_all(t, head, 4, deadline, err, nerr);
    uint32_t n = r == 0 ? get32(head) : 0;
    if (r == 0 && (n < 4 || n > REPLY_MAX)) {
        snprintf(err, nerr, "the server at %s answered the handshake with a malformed frame (length %u): is it a "
                 "bearing model server?", hostport, n);
        r = -1;
    }
    char msg[REPLY_MAX + 1];
    if (r == 0) r = recv_all(t, head + 4, 4, deadline, err, nerr);
    if (r == 0) r = recv_all(t, (unsigned char *)msg, n - 4, deadline, err, nerr);
    if (r == -2) snprintf(err, nerr, "the server at %s did not answer the handshake within %g s", hostport, timeout);
    if (r == 0) {
        msg[n - 4] = '\0';
        if (get32(head + 4) != 0) {
            snprintf(err, nerr, "the model server at %s refused the instance: %s", hostport, msg);
            r = -1;
        }
    }
    if (r != 0) {
        btcp_close(t);
        return NULL;
    }
    return t;
}

int btcp_call(BTcp *t, uint32_t cmd, const unsigned char *req, size_t reqlen, BTcpHead *head, unsigned char *body,
              size_t cap, size_t *blen, double timeout, char *err, size_t nerr) {
    unsigned char h[36];
    put32(h, (uint32_t)(4 + reqlen));
    put32(h + 4, cmd);
    double deadline = mono() + timeout;
    int r = send_two(t, h, 8, req, reqlen, err, nerr);
    if (r == 0) r = recv_all(t, h, 8, deadline, err, nerr);
    if (r != 0) return r;
    uint32_t n = get32(h), kind = get32(h + 4);
    if (kind == 1) { /* the server's report of the model process's end */
        if (n < 4 || n > FAULT_MAX + 4) {
            snprintf(err, nerr, "the model server at %s sent a malformed fault frame (length %u)", t->peer, n);
            return -1;
        }
        char *m = (char *)malloc(n - 4 + 1);
        if (!m) { snprintf(err, nerr, "out of memory"); return -1; }
        r = recv_all(t, (unsigned char *)m, n - 4, deadline, err, nerr);
        if (r == 0) {
            m[n - 4] = '\0';
            snprintf(err, nerr, "%s (model server at %s)", m, t->peer);
            r = -1;
        }
        free(m);
        return r;
    }
    if (kind != 0 || n < 32 || n - 32 > cap || n > FRAME_MAX) {
        snprintf(err, nerr, "the model server at %s sent a malformed frame (kind %u, length %u; allowed: 32..%zu)",
                 t->peer, kind, n, cap + 32 < FRAME_MAX ? cap + 32 : (size_t)FRAME_MAX);
        return -1;
    }
    r = recv_all(t, h + 8, 28, deadline, err, nerr);
    if (r == 0) r = recv_all(t, body, n - 32, deadline, err, nerr);
    if (r != 0) return r;
    memcpy(&head->status, h + 8, 4);
    memcpy(&head->mode, h + 12, 4);
    memcpy(&head->flags, h + 16, 4);
    memcpy(&head->time, h + 20, 8);
    memcpy(&head->busy, h + 28, 8);
    *blen = n - 32;
    return 0;
}

void btcp_close(BTcp *t) {
    if (!t) return;
    if (t->s != BAD_SOCK) {
#ifdef _WIN32
        shutdown(t->s, SD_BOTH);
#else
        shutdown(t->s, SHUT_RDWR);
#endif
        close_sock(t->s);
    }
    free(t);
}

const char *btcp_peer(const BTcp *t) { return t ? t->peer : ""; }

void *btcp_buffer(size_t n) {
#ifdef _WIN32
    return VirtualAlloc(NULL, n, MEM_RESERVE | MEM_COMMIT, PAGE_READWRITE);
#else
    void *p = mmap(NULL, n, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    return p == MAP_FAILED ? NULL : p;
#endif
}

void btcp_buffer_free(void *p, size_t n) {
    if (!p) return;
#ifdef _WIN32
    (void)n;
    VirtualFree(p, 0, MEM_RELEASE);
#else
    munmap(p, n);
#endif
}
