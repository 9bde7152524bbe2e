/* TCP transport of the bearing FMU's native layer: the FMI calls of an instance go to a model process of the
 * model server (bearing serve, bearing_cosim/fmu_server.py) instead of a local one. POSIX and Winsock.
 *
 * Frames are length-prefixed and bounded (little-endian):
 *   handshake: "BRGT", token; then protocol, GUID; the server replies with a code and a message
 *   request:   u32 length, u32 command, the request bytes of the shared-memory layout
 *   response:  u32 length, u32 kind (0: response, 1: fault text from the server), i32 status, u32 mode,
 *              u32 flags, f64 time, f64 busy, the response bytes
 */
#ifndef BEARING_TCP_H
#define BEARING_TCP_H
#include <stddef.h>
#include <stdint.h>

typedef struct BTcp BTcp;
typedef struct {
    int32_t status;
    uint32_t mode, flags;
    double time, busy;
} BTcpHead;

#define BTCP_DEFAULT_SERVER "127.0.0.1:7410"

/* Connects to host:port and completes the handshake within timeout seconds; NULL with the reason in err. */
BTcp *btcp_connect(const char *hostport, const char *token, uint32_t protocol, const char *guid, double timeout,
                   char *err, size_t nerr);
/* One exchange: 0 with head and body (at most cap bytes, *blen); otherwise the reason in err (the connection
 * is then unusable): -1 transport failure or a fault reported by the server, -2 no answer within timeout. */
int btcp_call(BTcp *t, uint32_t cmd, const unsigned char *req, size_t reqlen, BTcpHead *head, unsigned char *body,
              size_t cap, size_t *blen, double timeout, char *err, size_t nerr);
void btcp_close(BTcp *t);
const char *btcp_peer(const BTcp *t);
/* A zeroed buffer of n bytes for the request and response areas (pages committed when touched). */
void *btcp_buffer(size_t n);
void btcp_buffer_free(void *p, size_t n);
#endif
