package io.robomw.it.console;

import io.robomw.testkit.Ports;
import io.robomw.agents.host.AgentHost;
import io.robomw.agents.host.ClusterKey;
import io.robomw.api.AgentRef;
import io.robomw.api.AgentStatus;
import io.robomw.examples.agents.SquareSurveyAgent;
import io.robomw.it.demo.MwProcess;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.MethodOrderer;
import org.junit.jupiter.api.Order;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestMethodOrder;
import org.junit.jupiter.api.io.TempDir;
import org.openqa.selenium.By;
import org.openqa.selenium.OutputType;
import org.openqa.selenium.TakesScreenshot;
import org.openqa.selenium.WebElement;
import org.openqa.selenium.chrome.ChromeDriver;
import org.openqa.selenium.chrome.ChromeDriverService;
import org.openqa.selenium.chrome.ChromeOptions;
import org.openqa.selenium.support.ui.WebDriverWait;

import java.io.File;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.time.Duration;
import java.util.concurrent.TimeUnit;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

/**
 * The console as a user sees it, in a real browser: two agent hosts (one with a simulated robot
 * it serves), the console, each in its own JVM, and Debian's headless Chromium driven through its
 * chromedriver by Selenium. Checks the hosts and the agents where they really are, the robot moving
 * on the map, the retract button bringing an agent home, and a host that goes away (shown down,
 * its agents greyed as last seen) and comes back. Screenshots go to target/console-screenshots.
 */
@TestMethodOrder(MethodOrderer.OrderAnnotation.class)
class ConsoleBrowserIT {

    private static final String PASSPHRASE = "console it cluster";
    private static final ClusterKey KEY = ClusterKey.fromPassphrase(PASSPHRASE);
    private static final Duration WITHIN = Duration.ofSeconds(30);
    private static final Path SHOTS = Path.of("target", "console-screenshots");

    @TempDir
    static Path dir;
    static MwProcess alpha;
    static MwProcess beta;
    static MwProcess console;
    static AgentHost home;
    static ChromeDriver browser;
    static int betaPort;
    static String[] betaArgs;
    static AgentRef survey;

    @BeforeAll
    static void start() throws Exception {
        Path keyFile = dir.resolve("cluster.key");
        Files.writeString(keyFile, PASSPHRASE + "\n");
        Path robotPassword = Files.writeString(dir.resolve("robot.password"), "console robot\n");
        Path world = MwProcess.CHECKOUT.resolve("examples/worlds/arena.yaml");
        int alphaPort = Ports.free();
        int robotPort = Ports.free();
        betaPort = Ports.free();
        alpha = MwProcess.start("console-it-alpha", "host", "--name", "alpha", "--port", String.valueOf(alphaPort), "--world", world.toString(),
                "--world-robot", "nxt", "--serve", "tcp://127.0.0.1:" + robotPort, "--serve-password-file", robotPassword.toString(),
                "--key-file", keyFile.toString());
        betaArgs = new String[] {"host", "--name", "beta", "--port", String.valueOf(betaPort), "--key-file", keyFile.toString()};
        beta = MwProcess.start("console-it-beta", betaArgs);
        alpha.await(" ready at ", WITHIN);
        beta.await(" ready at ", WITHIN);
        console = MwProcess.start("console-it-console", "console", "--host", "rmi://127.0.0.1:" + alphaPort + "/alpha",
                "--host", "rmi://127.0.0.1:" + betaPort + "/beta", "--robot", "tcp://127.0.0.1:" + robotPort + "/nxt?password-file=" + robotPassword, "--world", world.toString(),
                "--port", "0", "--period-ms", "300", "--key-file", keyFile.toString(), "--record", recording().toString());
        String page = console.await("console at http://127.0.0.1:", WITHIN).replace("console at ", "").trim();
        assertTrue(page.contains("#token="), page);
        home = AgentHost.builder("it-console-home").clusterKey(KEY).start();
        browser = chromium();
        browser.get(page);
        Files.createDirectories(SHOTS);
    }

    /** Debian's chromium through Debian's chromedriver: nothing is downloaded, nothing leaves loopback. */
    static ChromeDriver chromium() throws IOException {
        File driver = new File("/usr/bin/chromedriver");
        File binary = new File("/usr/bin/chromium");
        assertTrue(driver.canExecute() && binary.canExecute(),
                "the browser test needs Debian's chromium and chromium-driver: apt-get install -y chromium chromium-driver (.ci/run does)");
        ChromeOptions options = new ChromeOptions();
        options.setBinary(binary);
        options.addArguments("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
                "--disable-sync", "--no-first-run", "--disable-dev-shm-usage", "--window-size=1400,900",
                "--user-data-dir=" + Files.createTempDirectory(dir, "chromium-profile"));
        ChromeDriverService service = new ChromeDriverService.Builder().usingDriverExecutable(driver).usingAnyFreePort()
                .withLogFile(Path.of("target", "it-logs", "console-it-chromedriver.log").toFile()).build();
        return new ChromeDriver(service, options);
    }

    @AfterAll
    static void stop() throws Exception {
        if (browser != null) {
            browser.quit();
        }
        if (home != null) {
            home.close();
        }
        for (MwProcess p : new MwProcess[] {console, beta, alpha}) {
            if (p != null) {
                p.close();
            }
        }
    }

    @Test
    @Order(1)
    void thePageShowsBothHostsUpWithTheirRobotsAndTheWorld() {
        waitFor("both hosts listed as up", () -> hostCard("alpha").getAttribute("data-up").equals("true")
                && hostCard("beta").getAttribute("data-up").equals("true"));
        assertEquals("nxt", read(() -> hostCard("alpha").findElement(By.cssSelector("[data-field=robot]")).getText()));
        assertEquals("none", read(() -> hostCard("beta").findElement(By.cssSelector("[data-field=robot]")).getText()));
        assertEquals("none", read(() -> hostCard("alpha").findElement(By.cssSelector("[data-field=owed]")).getText()));
        assertEquals("arena", read(() -> browser.findElement(By.id("world-name")).getAttribute("textContent")));
        assertEquals("live", read(() -> browser.findElement(By.id("link")).getAttribute("data-state")));
    }

    @Test
    @Order(2)
    void agentsAppearAtTheHostsTheyAreAtAndTheRobotMovesOnTheMap() throws Exception {
        double[] before = robotOnMap("nxt");
        survey = home.agency().sendAgent(hostAddress("alpha"), new SquareSurveyAgent(0.4));
        AgentRef lingering = home.agency().sendAgent(hostAddress("beta"), lingering(40));
        waitFor("the survey agent listed at alpha", () -> !hostCard("alpha").findElements(agentSelector(survey)).isEmpty());
        waitFor("the lingering agent listed at beta", () -> !hostCard("beta").findElements(agentSelector(lingering)).isEmpty());
        assertTrue(read(() -> hostCard("beta").findElement(agentSelector(lingering)).getText()).contains("LingeringAgent"));
        waitFor("the robot moved at least 10 cm on the map", () -> {
            double[] now = robotOnMap("nxt");
            return Math.hypot(now[0] - before[0], now[1] - before[1]) > 0.10;
        });
        double[] now = robotOnMap("nxt");
        assertTrue(now[0] > 0 && now[0] < 4 && now[1] > 0 && now[1] < 3, "the robot is drawn inside the 4 x 3 m arena: " + now[0] + ", " + now[1]);
        waitFor("a report of the survey shows in the events", () -> !browser.findElements(By.cssSelector("#events li[data-what=report][data-agent='"
                + survey.id() + "']")).isEmpty());
        screenshot("console-live");
        lingering.dispose();
    }

    @Test
    @Order(3)
    void theRetractButtonBringsAnAgentHome() throws Exception {
        AgentRef lingering = home.agency().sendAgent(hostAddress("beta"), lingering(200));
        waitFor("the agent listed at beta", () -> !hostCard("beta").findElements(agentSelector(lingering)).isEmpty());
        By retract = By.cssSelector(".host[data-host=beta] [data-agent='" + lingering.id() + "'] button[data-action=retract]");
        waitFor("its retract button is enabled", () -> browser.findElement(retract).isEnabled());
        waitFor("the retract button pressed", () -> {
            browser.findElement(retract).click();
            return true;
        });
        waitFor("the agent is home, retracted", () -> lingering.status() == AgentStatus.RETRACTED);
        waitFor("the page no longer lists it at beta", () -> hostCard("beta").findElements(agentSelector(lingering)).isEmpty());
        waitFor("the page tells it went home", () -> !browser.findElements(By.cssSelector("#events li[data-what=retracted][data-agent='"
                + lingering.id() + "']")).isEmpty());
        waitFor("the page says what the button did", () -> browser.findElement(By.id("toast")).getText().contains("retract of agent"));
    }

    @Test
    @Order(4)
    void aHostThatGoesAwayIsShownDownWithItsAgentsStaleAndComesBack() throws Exception {
        AgentRef lingering = home.agency().sendAgent(hostAddress("beta"), lingering(200));
        waitFor("the agent listed at beta", () -> !hostCard("beta").findElements(agentSelector(lingering)).isEmpty());
        beta.kill();
        waitFor("beta shown down", () -> hostCard("beta").getAttribute("data-up").equals("false"));
        assertTrue(read(() -> hostCard("beta").getAttribute("class")).contains("stale"), "a down host's card is greyed");
        assertTrue(read(() -> !hostCard("beta").findElements(agentSelector(lingering)).isEmpty()), "its agent is still shown, as last seen");
        String text = read(() -> hostCard("beta").getText());
        assertTrue(text.contains("as last seen"), text);
        assertTrue(read(() -> !hostCard("beta").findElement(agentSelector(lingering)).findElement(By.cssSelector("button[data-action=retract]")).isEnabled()),
                "no retract at a host that is down");
        screenshot("console-host-down");
        beta = MwProcess.start("console-it-beta-again", betaArgs);
        beta.await(" ready at ", WITHIN);
        waitFor("beta shown up again", () -> hostCard("beta").getAttribute("data-up").equals("true"));
        waitFor("its card no longer greyed", () -> !hostCard("beta").getAttribute("class").contains("stale"));
        survey.result().get(60, TimeUnit.SECONDS);
        screenshot("console-after");
        By stop = By.cssSelector(".card[data-robot=nxt] button[data-action=stop]");
        waitFor("the robot's stop button is enabled", () -> browser.findElement(stop).isEnabled());
        waitFor("the stop button pressed", () -> {
            browser.findElement(stop).click();
            return true;
        });
        waitFor("the page says the robot stopped", () -> browser.findElement(By.id("toast")).getText().contains("robot nxt stopped"));
    }

    @Test
    @Order(5)
    void whatTheConsoleRecordedReplaysIntoAPicture() throws Exception {
        console.close(); // SIGTERM, as Ctrl-C: the recording gets its summary and footer
        console = null;
        Path png = dir.resolve("replay.png");
        try (MwProcess replay = MwProcess.start("console-it-replay", "replay", recording().toString(), "--speed", "0", "--no-console", "--png",
                png.toString())) {
            String played = replay.await("replayed ", WITHIN);
            assertTrue(played.matches("replayed \\d+ messages .*") && !played.contains("ends early"), played);
            replay.await("wrote " + png, WITHIN);
            assertEquals(0, replay.waitFor(WITHIN));
        }
        assertTrue(Files.size(png) > 10_000, "a picture of the arena and the robot's path");
    }

    private static Path recording() {
        return Path.of("target", "console-it.mcap").toAbsolutePath();
    }

    private static LingeringAgent lingering(int rounds) {
        LingeringAgent a = new LingeringAgent();
        a.itinerary().repeat(rounds);
        return a;
    }

    private static String hostAddress(String name) {
        return "rmi://127.0.0.1:" + (name.equals("beta") ? betaPort : portOf(alpha)) + "/" + name;
    }

    private static int portOf(MwProcess p) {
        String line = p.output().lines().filter(l -> l.contains(" ready at ")).findFirst().orElseThrow();
        return Integer.parseInt(line.replaceAll(".* ready at rmi://[^:]+:(\\d+)/.*", "$1"));
    }

    private static By agentSelector(AgentRef ref) {
        return By.cssSelector("[data-agent='" + ref.id() + "']");
    }

    private static WebElement hostCard(String name) {
        return browser.findElement(By.cssSelector(".host[data-host='" + name + "']"));
    }

    private static double[] robotOnMap(String name) {
        waitFor("robot " + name + " drawn on the map", () -> !browser.findElements(By.id("robot-" + name)).isEmpty());
        return read(() -> {
            WebElement r = browser.findElement(By.id("robot-" + name));
            return new double[] {Double.parseDouble(r.getAttribute("data-x")), Double.parseDouble(r.getAttribute("data-y"))};
        });
    }

    /** Reads the page, again if it redrew what was being read. */
    private static <T> T read(java.util.function.Supplier<T> what) {
        Object[] value = new Object[1];
        waitFor("reading the page", () -> {
            value[0] = what.get();
            return true;
        });
        @SuppressWarnings("unchecked")
        T t = (T) value[0];
        return t;
    }

    /** Waits for what the page shows, re-reading it (the page redraws, so elements are looked up afresh each time). */
    private static void waitFor(String what, java.util.function.BooleanSupplier condition) {
        new WebDriverWait(browser, WITHIN).withMessage(what).ignoring(org.openqa.selenium.NoSuchElementException.class)
                .ignoring(org.openqa.selenium.StaleElementReferenceException.class).until(d -> condition.getAsBoolean());
    }

    private static void screenshot(String name) throws IOException {
        File shot = ((TakesScreenshot) browser).getScreenshotAs(OutputType.FILE);
        Files.copy(shot.toPath(), SHOTS.resolve(name + ".png"), StandardCopyOption.REPLACE_EXISTING);
    }
}
