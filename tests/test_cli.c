/* SPDX-License-Identifier: MIT */
/* The command-line helpers every tool shares (libcore/tools/cli.c): the
 * output written through a temporary, and what a signal does to it. Each
 * signal case runs in a child process (fork) that opens an output, writes
 * part of it and raises the signal; the parent checks how the child ended,
 * its message and that the directory holds exactly what it held before. */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"
#include "conica_test.h"

/* A fresh directory under TMPDIR (or /tmp) for one case. */
static void make_dir(char *dir, size_t cap)
{
    const char *base = getenv("TMPDIR");
    snprintf(dir, cap, "%s/conica-test-cli.XXXXXX", base && *base ? base : "/tmp");
    REQUIRE(mkdtemp(dir) != NULL);
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    REQUIRE(f != NULL);
    fputs(text, f);
    REQUIRE(fclose(f) == 0);
}

/* The whole file in a static buffer ("" when missing). */
static const char *read_text(const char *path)
{
    static char buf[4096];
    FILE *f = fopen(path, "rb");
    size_t n = 0;
    buf[0] = '\0';
    if (f) {
        n = fread(buf, 1, sizeof buf - 1, f);
        fclose(f);
    }
    buf[n] = '\0';
    return buf;
}

/* The names in dir (hidden ones too), sorted, one per line. */
static void list_dir(const char *dir, char *out, size_t cap)
{
    char names[16][256];
    size_t n = 0, i, j, k = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    REQUIRE(d != NULL);
    while ((e = readdir(d)) != NULL && n < 16)
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
            snprintf(names[n++], sizeof names[0], "%s", e->d_name);
    closedir(d);
    for (i = 1; i < n; i++)
        for (j = i; j > 0 && strcmp(names[j - 1], names[j]) > 0; j--) {
            char t[256];
            memcpy(t, names[j], sizeof t);
            memcpy(names[j], names[j - 1], sizeof t);
            memcpy(names[j - 1], t, sizeof t);
        }
    out[0] = '\0';
    for (i = 0; i < n; i++)
        k += (size_t)snprintf(out + k, cap - k, "%s\n", names[i]);
}

static void remove_dir(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char p[1024];
    if (!d)
        return;
    while ((e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
            snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
            unlink(p);
        }
    closedir(d);
    rmdir(dir);
}

/* In a child: stderr to errpath, open target, write, raise signo (set to
 * SIG_IGN first with `ignored`, to SIG_DFL without), then commit. Returns the
 * child's wait status. */
static int run_child(const char *target, const char *errpath, int signo, int ignored)
{
    pid_t pid;
    int status = 0;
    fflush(NULL);
    pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        cli_output out;
        if (!freopen(errpath, "w", stderr))
            _exit(90);
        /* The signal's disposition as the case wants it, whatever this
         * process inherited: a job started in the background by a
         * non-interactive shell (CI's, for one) has SIGINT and SIGQUIT
         * ignored, and the tools rightly leave an inherited SIG_IGN alone. */
        signal(signo, ignored ? SIG_IGN : SIG_DFL);
        if (cli_output_open("tool", target, &out) != 0)
            _exit(91);
        fputs("new content, half written\n", out.f);
        fflush(out.f);
        raise(signo);
        if (cli_output_commit("tool", &out) != 0)
            _exit(92);
        _exit(0);
    }
    REQUIRE(waitpid(pid, &status, 0) == pid);
    return status;
}

TEST_CASE("a signal while the temporary exists removes it and ends the tool with 128+signo",
          "[cli][signals]")
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGXFSZ, SIGQUIT,
                               SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGXCPU, SIGABRT};
    static const char *names[] = {"SIGINT",  "SIGTERM", "SIGHUP",  "SIGPIPE",
                                  "SIGXFSZ", "SIGQUIT", "SIGUSR1", "SIGUSR2",
                                  "SIGALRM", "SIGVTALRM", "SIGXCPU", "SIGABRT"};
    size_t i;
    for (i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        char dir[512], target[600], errpath[600], before[4096], after[4096], want[700];
        int status;
        INFO("signal %s", names[i]);
        make_dir(dir, sizeof dir);
        snprintf(target, sizeof target, "%s/out.txt", dir);
        snprintf(errpath, sizeof errpath, "%s/../conica-test-cli-err.%d", dir, (int)getpid());
        write_file(target, "old content\n");
        list_dir(dir, before, sizeof before);
        status = run_child(target, errpath, sigs[i], 0);
        if (sigs[i] == SIGXFSZ) {
            /* exits instead of dying of it: its default action dumps core */
            CHECK(WIFEXITED(status));
            CHECK_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 128 + SIGXFSZ);
        } else {
            /* dies of the signal itself: a shell reports 128 + signo */
            CHECK(WIFSIGNALED(status));
            CHECK_EQ(WIFSIGNALED(status) ? WTERMSIG(status) : -1, sigs[i]);
        }
        list_dir(dir, after, sizeof after);
        INFO("before:\n%s after:\n%s", before, after);
        CHECK(strcmp(before, after) == 0); /* no temporary left */
        CHECK(strcmp(read_text(target), "old content\n") == 0);
        snprintf(want, sizeof want, "tool: error: %s: stopped by %s", target, names[i]);
        INFO("stderr: %s", read_text(errpath));
        CHECK(strstr(read_text(errpath), want) != NULL);
        CHECK(strstr(read_text(errpath), "output not written") != NULL);
        unlink(errpath);
        remove_dir(dir);
    }
}

TEST_CASE("a signal the tool was started with ignored stays ignored", "[cli][signals]")
{
    char dir[512], target[600], errpath[600];
    int status;
    make_dir(dir, sizeof dir);
    snprintf(target, sizeof target, "%s/out.txt", dir);
    snprintf(errpath, sizeof errpath, "%s/err", dir);
    status = run_child(target, errpath, SIGHUP, 1); /* as under nohup */
    CHECK(WIFEXITED(status));
    CHECK_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0);
    CHECK(strcmp(read_text(target), "new content, half written\n") == 0);
    remove_dir(dir);
}

TEST_CASE("the temporary is a hidden file named after the target, beside it", "[cli]")
{
    char dir[512], target[600], prefix[700], before[4096], after[4096];
    struct sigaction sa, term0, int0;
    cli_output out;
    /* what was there before (the test runner may catch signals itself) */
    REQUIRE(sigaction(SIGTERM, NULL, &term0) == 0);
    REQUIRE(sigaction(SIGINT, NULL, &int0) == 0);
    make_dir(dir, sizeof dir);
    snprintf(target, sizeof target, "%s/out.txt", dir);
    snprintf(prefix, sizeof prefix, ".out.txt.conica-tmp.");
    list_dir(dir, before, sizeof before);
    REQUIRE(cli_output_open("tool", target, &out) == 0);
    REQUIRE(out.tmp != NULL);
    /* the name in the directory handle's directory (the one it gets at
     * the latest at the commit, with O_TMPFILE) */
    CHECK(strncmp(out.tmp, prefix, strlen(prefix)) == 0);
    CHECK_EQ_U(strlen(out.tmp), strlen(prefix) + 6);
    CHECK(out.dirfd >= 0);
    CHECK_STR_EQ(out.base, "out.txt");
    /* while it exists the handler is installed, after the commit it is not */
    REQUIRE(sigaction(SIGTERM, NULL, &sa) == 0);
    CHECK(sa.sa_handler != term0.sa_handler);
    fputs("x\n", out.f);
    REQUIRE(cli_output_commit("tool", &out) == 0);
    REQUIRE(sigaction(SIGTERM, NULL, &sa) == 0);
    CHECK(sa.sa_handler == term0.sa_handler);
    list_dir(dir, after, sizeof after);
    CHECK(strcmp(after, "out.txt\n") == 0);
    CHECK(strcmp(read_text(target), "x\n") == 0);
    /* abort: the same */
    REQUIRE(cli_output_open("tool", target, &out) == 0);
    cli_output_abort(&out);
    REQUIRE(sigaction(SIGINT, NULL, &sa) == 0);
    CHECK(sa.sa_handler == int0.sa_handler);
    list_dir(dir, after, sizeof after);
    CHECK(strcmp(after, "out.txt\n") == 0);
    /* a name without a directory: the temporary is in the working directory */
    REQUIRE(chdir(dir) == 0);
    REQUIRE(cli_output_open("tool", "plain.txt", &out) == 0);
    CHECK(strncmp(out.tmp, ".plain.txt.conica-tmp.", 22) == 0);
    cli_output_abort(&out);
    REQUIRE(chdir("/") == 0);
    remove_dir(dir);
}
